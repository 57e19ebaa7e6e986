#pragma once
/// \file All-or-nothing outputs of one run.
///
/// A command registers every file (and directory) it is going to write before it does any
/// work; the set checks them all at once and hands out staging paths next to each target.
/// The run writes its outputs there, and only when every one of them has been written does
/// commit() move them into place. If anything fails, the destructor removes what was staged
/// and no target is touched: a run leaves either all of its outputs or none.
///
/// Registration refuses, before any work is done:
/// - two outputs that resolve to the same file (after `.`/`..`, symbolic links and hard links:
///   `-o X.off --report X.off`, or `-o p.node --report p.ele` where `.node` also writes `.ele`);
/// - an output that resolves to one of the run's inputs (inputs are never overwritten);
/// - an existing target that is not a regular file (a device, FIFO, socket or a path such as
///   /dev/stdout that does not resolve to a file), or a directory where a file is expected;
/// - an output whose directory does not exist or cannot be written (a placeholder is created
///   in it on registration);
/// - an input or another output inside an output directory.
///
/// commit() first links every existing target aside, then moves the staged outputs over
/// them; if a move fails, the moves already made are undone and the old targets restored, so
/// a failed commit also leaves the targets as they were. A replaced file keeps its permission
/// bits. With install_output_cleanup_on_signals(), SIGINT, SIGTERM and SIGHUP remove the
/// staged files of every live set before the process dies.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace dynmesh {

class OutputSet {
public:
    /// When an output is moved into place: reports go last, so that a report exists only
    /// when every output it describes does.
    enum class Order { Normal, Last };

    /// `inputs`: the files the run reads (missing or empty entries are ignored).
    explicit OutputSet(std::vector<std::filesystem::path> inputs = {});
    OutputSet(const OutputSet&) = delete;
    OutputSet& operator=(const OutputSet&) = delete;
    /// Removes every staged output that was not committed.
    ~OutputSet();

    /// Registers the output file `target`; `what` names the argument in messages (e.g. "-o",
    /// "--report"). Returns the staging path to write it to: a new file in the target's
    /// directory whose name ends with the target's extension.
    /// \throw InvalidInput naming both arguments on a clash or a bad target (see the file
    ///        comment).
    std::filesystem::path add_file(const std::filesystem::path& target, std::string_view what,
                                   Order order = Order::Normal);

    /// Registers the files `base + ext` for every ext in `extensions` (one writer making a
    /// set, e.g. Triangle's OUT.node + OUT.ele); returns the staging base, to which the
    /// writer appends the same extensions.
    std::filesystem::path add_file_set(const std::filesystem::path& base,
                                       const std::vector<std::string>& extensions,
                                       std::string_view what);

    /// Registers the output directory `target` (created on commit if missing); returns a
    /// staging directory (inside `target` when it exists, beside it otherwise). On commit,
    /// every entry written there is moved into `target`, replacing files of the same name;
    /// other files in `target` are left alone.
    std::filesystem::path add_directory(const std::filesystem::path& target, std::string_view what);

    /// A private scratch directory beside `near` (an output target already registered, whose
    /// directory is known to be writable) for intermediate files; it is removed with the
    /// set, committed or not, and by the signal cleanup.
    std::filesystem::path scratch_directory(const std::filesystem::path& near);

    /// Moves every staged output into place (Order::Last ones after the others).
    /// \throw IoError naming the target when a move fails; the targets are then restored.
    void commit();

    /// Whether commit() has completed.
    [[nodiscard]] bool committed() const { return committed_; }

private:
    struct Entry {
        std::filesystem::path target;    ///< as given (messages)
        std::filesystem::path resolved;  ///< absolute, normalised, links followed
        std::filesystem::path staged;    ///< where the run writes it
        std::string what;
        bool directory = false;
        bool inside_target = false;  ///< a directory staged inside its existing target
        bool scratch = false;        ///< never moved into place
        Order order = Order::Normal;
        int cleanup_slot = -1;  ///< slot of the signal-cleanup table
    };
    std::filesystem::path reserve(const std::filesystem::path& target, std::string_view what,
                                  bool directory, Order order);
    void check_clashes(const Entry& e) const;
    void forget(Entry& e);

    std::vector<Entry> inputs_;
    std::vector<Entry> outputs_;
    bool committed_ = false;
};

/// Installs handlers for SIGINT, SIGTERM and SIGHUP that remove the staged outputs of every
/// live OutputSet, then let the signal end the process as it would have. For programs (the
/// CLI); a library user with handlers of its own need not call it. Idempotent.
void install_output_cleanup_on_signals();

}  // namespace dynmesh
