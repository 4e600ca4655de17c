#pragma once
// Internal: fmt for the services library. medax_services does not link fmt::fmt yet (its
// target is in framework/CMakeLists.txt, a kernel file), so the services use fmt header-only:
// every services .cpp that formats includes fmt through this header, first, and never
// <fmt/...> directly. Once medax_services links fmt::fmt, this header can go.
#ifndef FMT_HEADER_ONLY
#define FMT_HEADER_ONLY
#endif
#include <fmt/format.h>
