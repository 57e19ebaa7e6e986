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
/// - an output whose directory does not exist or cannot be written (a placeholder is created
///   in it on registration), or that names an existing directory;
/// - an input or another output inside an output directory.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace dynmesh {

class OutputSet {
public:
    /// `inputs`: the files the run reads (missing or empty entries are ignored).
    explicit OutputSet(std::vector<std::filesystem::path> inputs = {});
    OutputSet(const OutputSet&) = delete;
    OutputSet& operator=(const OutputSet&) = delete;
    /// Removes every staged output that was not committed.
    ~OutputSet();

    /// Registers the output file `target`; `what` names the argument in messages (e.g. "-o",
    /// "--report"). Returns the staging path to write it to: a new file in the target's
    /// directory whose name ends with the target's file name (so its extension is kept).
    /// \throw InvalidInput naming both arguments on a clash or a bad directory (see the
    ///        file comment).
    std::filesystem::path add_file(const std::filesystem::path& target, std::string_view what);

    /// Registers the files `base + ext` for every ext in `extensions` (one writer making a
    /// set, e.g. Triangle's OUT.node + OUT.ele); returns the staging base, to which the
    /// writer appends the same extensions.
    std::filesystem::path add_file_set(const std::filesystem::path& base,
                                       const std::vector<std::string>& extensions,
                                       std::string_view what);

    /// Registers the output directory `target` (created on commit if missing); returns a
    /// staging directory. On commit, every entry written there is moved into `target`,
    /// replacing files of the same name; other files in `target` are left alone.
    std::filesystem::path add_directory(const std::filesystem::path& target, std::string_view what);

    /// Moves every staged output into place, in registration order.
    /// \throw IoError naming the target when a move fails (the system then refused a rename
    ///        within one directory; the outputs moved before it stay in place).
    void commit();

    /// Whether commit() has completed.
    [[nodiscard]] bool committed() const { return committed_; }

private:
    struct Entry {
        std::filesystem::path target;   ///< as given (messages)
        std::filesystem::path resolved; ///< absolute, normalised, links followed
        std::filesystem::path staged;   ///< where the run writes it
        std::string what;
        bool directory = false;
    };
    std::filesystem::path reserve(const std::filesystem::path& target, std::string_view what,
                                  bool directory);
    void check_clashes(const Entry& e) const;

    std::vector<Entry> inputs_;
    std::vector<Entry> outputs_;
    bool committed_ = false;
};

}  // namespace dynmesh
