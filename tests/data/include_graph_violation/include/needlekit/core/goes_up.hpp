// A core header that includes the FE solver: an include that goes up (checked by architecture.include_graph_catches).
#pragma once
#include "needlekit/fem/quasi_static_solver.hpp"
