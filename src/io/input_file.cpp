#include "dynmesh/io/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>

#include "dynmesh/error.hpp"
#include "io_common.hpp"

namespace dynmesh {

namespace detail {

namespace {

/// Closes a descriptor on scope exit.
struct Descriptor {
    int fd = -1;
    ~Descriptor() {
        if (fd >= 0) ::close(fd);
    }
};

std::string size_text(std::uint64_t bytes) {
    if (bytes >= (std::uint64_t{1} << 30) && bytes % (std::uint64_t{1} << 30) == 0)
        return std::to_string(bytes >> 30) + " GiB";
    if (bytes >= (std::uint64_t{1} << 20) && bytes % (std::uint64_t{1} << 20) == 0)
        return std::to_string(bytes >> 20) + " MiB";
    return std::to_string(bytes) + " bytes";
}

}  // namespace

std::string load_file(const std::filesystem::path& path, const FileContext& ctx,
                      std::uint64_t max_bytes) {
    // The type is checked before the file is opened (opening a device can have effects of
    // its own), and again on the open descriptor, which must be the same file: a path
    // swapped for a FIFO or a device between the two checks is caught.
    const auto refuse_type = [&](mode_t mode) {
        if (S_ISDIR(mode)) ctx.fail("is a directory, not a file");
        if (S_ISFIFO(mode)) ctx.fail("is a pipe (FIFO), not a regular file");
        if (S_ISCHR(mode) || S_ISBLK(mode)) ctx.fail("is a device, not a regular file");
        if (!S_ISREG(mode)) ctx.fail("is not a regular file");
    };
    struct stat before {};
    if (::stat(path.c_str(), &before) != 0) {
        const int err = errno;
        if (err == ENOENT) ctx.fail("no such file");
        if (err == ENOTDIR) ctx.fail("no such file (a component of the path is not a directory)");
        ctx.fail("cannot access the file: " + errno_text(err));
    }
    refuse_type(before.st_mode);
    // O_NONBLOCK: should the path have become a FIFO, opening it must not block.
    Descriptor file;
    errno = 0;
    file.fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (file.fd < 0) ctx.fail("cannot open the file: " + errno_text(errno));
    struct stat st {};
    if (::fstat(file.fd, &st) != 0) ctx.fail("cannot access the file: " + errno_text(errno));
    refuse_type(st.st_mode);
    if (st.st_dev != before.st_dev || st.st_ino != before.st_ino)
        ctx.fail("the file changed while it was opened");
    const auto size = static_cast<std::uint64_t>(st.st_size);
    if (size > max_bytes)
        ctx.fail("the file has " + std::to_string(size) + " bytes, more than the limit of " +
                 size_text(max_bytes) + " for this input");
    std::string data;
    try {
        data.resize(static_cast<std::size_t>(size));
    } catch (const std::bad_alloc&) {
        ctx.fail("file of " + std::to_string(size) + " bytes does not fit in memory");
    }
    std::size_t got = 0;
    while (got < data.size()) {
        const ssize_t n = ::read(file.fd, data.data() + got, data.size() - got);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0)
            ctx.fail("read error after " + std::to_string(got) + " of " + std::to_string(size) +
                     " bytes: " + errno_text(errno));
        if (n == 0)
            ctx.fail("the file shrank while it was read (" + std::to_string(got) + " of " +
                     std::to_string(size) + " bytes)");
        got += static_cast<std::size_t>(n);
    }
    return data;
}

}  // namespace detail

std::string read_input_file(const std::filesystem::path& path, std::uint64_t max_bytes) {
    return detail::load_file(path, detail::FileContext(path), max_bytes);
}

}  // namespace dynmesh
