#pragma once
/// \file The exception family of dynmesh and the two checking macros.
///
/// Caller mistakes (bad files, bad options, violated preconditions) throw a subclass of
/// `dynmesh::Error` whose message names the function, the element and what was expected, so
/// that callers can tell bad input (InvalidInput, IoError) from a broken mesh
/// (TopologyError) or from a bug of ours (InternalError).

#include <cstddef>
#include <stdexcept>
#include <string>

namespace dynmesh {

struct Error : std::runtime_error {
    using std::runtime_error::runtime_error;
};
/// A bad argument or option, or an input that violates a documented precondition.
struct InvalidInput : Error {
    using Error::Error;
    /// An error about one element of the caller's input (a point, vertex or face), given by its
    /// index in the span the caller passed, so that a caller reading a file can name the line.
    InvalidInput(const std::string& message, std::size_t element_index)
        : Error(message), element(element_index) {}
    static constexpr std::size_t kNoElement = static_cast<std::size_t>(-1);
    /// The index of the offending input element, or kNoElement.
    std::size_t element = kNoElement;
};
/// A file that cannot be read or written, or whose content is malformed.
struct IoError : Error {
    using Error::Error;
};
/// A mesh that is not (or would stop being) an oriented 2-manifold.
struct TopologyError : Error {
    using Error::Error;
};
/// An internal invariant failed: a bug in dynmesh.
struct InternalError : Error {
    using Error::Error;
};

namespace detail {
[[noreturn]] void throw_internal(const char* expr, const char* file, int line, const std::string& msg);
}  // namespace detail

}  // namespace dynmesh

/// Always-on check of a caller's precondition; throws `InvalidInput(msg)`.
#define DYNMESH_CHECK(cond, msg)                          \
    do {                                                  \
        if (!(cond)) throw ::dynmesh::InvalidInput(msg);  \
    } while (false)

/// Debug-build check of our own invariants; throws `InternalError` with file and line.
#ifdef NDEBUG
#define DYNMESH_ASSERT(cond, msg) \
    do {                          \
    } while (false)
#else
#define DYNMESH_ASSERT(cond, msg)                                                   \
    do {                                                                            \
        if (!(cond)) ::dynmesh::detail::throw_internal(#cond, __FILE__, __LINE__, msg); \
    } while (false)
#endif
