#pragma once
// A stage's parameter table in Markdown, made from its declarations: what
// `medax describe NAME --markdown` prints and what each docs/plugins page embeds between
//   <!-- params: NAME -->  and  <!-- /params -->
// (scripts/update-docs-params.sh rewrites those blocks; a test checks they are current).
#include <medax/stage.hpp>

#include <string>

namespace medax {

/// The Markdown table of `info.params` (a line saying there are none when empty).
std::string param_table_markdown(const StageInfo& info);

/// The block a docs page holds for stage `name`: the markers around the table.
std::string param_block_markdown(const StageInfo& info);

}  // namespace medax
