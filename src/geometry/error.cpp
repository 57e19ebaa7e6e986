#include "dynmesh/error.hpp"

namespace dynmesh::detail {

void throw_internal(const char* expr, const char* file, int line, const std::string& msg) {
    throw InternalError(std::string(file) + ":" + std::to_string(line) + ": assertion `" + expr +
                        "` failed: " + msg);
}

}  // namespace dynmesh::detail
