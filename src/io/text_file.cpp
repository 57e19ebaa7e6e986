#include "dynmesh/io/text_file.hpp"

#include "io_common.hpp"

namespace dynmesh {

void write_text_file(const std::filesystem::path& path, std::string_view text) {
    detail::AtomicWriter out(path);
    out.put(text);
    out.commit();
}

}  // namespace dynmesh
