#pragma once
/// @file pathpace.hpp
/// Umbrella header: everything a user of pathpace needs.

#include "pathpace/errors.hpp"
#include "pathpace/path.hpp"
