// A fixture: io (upstream) including plot (downstream); check_includes.py must refuse it.
#pragma once
#include "feint/plot/figures.hpp"
