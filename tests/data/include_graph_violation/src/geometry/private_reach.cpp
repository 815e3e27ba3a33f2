// A geometry source that reaches into another folder's private header.
#include "../io/toml_config.hpp"
