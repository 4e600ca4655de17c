#pragma once
// Everything a plugin author needs.
#include <medax/context.hpp>
#include <medax/geometry.hpp>
#include <medax/io.hpp>
#include <medax/medial_complex.hpp>
#include <medax/metrics.hpp>
#include <medax/params.hpp>
#include <medax/plugin.hpp>
#include <medax/stage.hpp>
#include <medax/surface.hpp>
#include <medax/version.hpp>
