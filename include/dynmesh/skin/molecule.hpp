#pragma once
/// \file Molecules for skin surfaces (specs/skin-surfaces.md §1.1, §6.4): atoms with a centre,
/// a van der Waals radius and an element, read from the plain formats (XYZR, PQR, weighted
/// points), the radius table that gives elements their radii (Bondi 1964 by default), and the
/// weighted points of the skin, w = r²/s (the sphere patch of an isolated atom then lies on
/// its van der Waals sphere).
///
/// Every reader refuses a bad file with IoError "<file>:<line>: <problem>" (a record that is
/// not numbers where numbers belong, a non-finite coordinate, a radius that is not positive, a
/// file without atoms).

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "dynmesh/geometry/vec.hpp"

namespace dynmesh {

struct Atom {
    Point3 center{};
    double radius = 0;     ///< van der Waals radius (Å), > 0
    std::string element;   ///< upper-case symbol ("C", "CL"); empty when the file does not say
    std::size_t line = 0;  ///< the line of the file it was read from (1-based; 0: not from a file)
};

/// A weighted point (z, w) of the skin's ball set: its power function is ‖x − z‖² − w.
struct WeightedPoint {
    Point3 center{};
    double weight = 0;
    bool operator==(const WeightedPoint&) const = default;
};

/// Van der Waals radii by element symbol (case-insensitive), with a fallback for elements the
/// table does not list.
class RadiusTable {
public:
    /// Bondi 1964 as the digest lists it (§6.4): H 1.20, C 1.70, N 1.55, O 1.52, F 1.47, P 1.80,
    /// S 1.80, Cl 1.75, Br 1.85, I 1.98 Å; 1.80 Å for any other element.
    [[nodiscard]] static RadiusTable bondi();
    /// A CSV table whose header names the columns `symbol` and `radius` (others are ignored;
    /// '#' starts a comment), e.g. ../shared/data/molecules/radii/bondi_vdw_radii.csv.
    /// \throw IoError naming the file and line of a bad row, a repeated symbol, a missing
    ///        column or an empty table.
    [[nodiscard]] static RadiusTable read_csv(const std::filesystem::path& path, double fallback = 1.80);

    /// The radius of `element`, or the fallback when it is not listed.
    [[nodiscard]] double radius(std::string_view element) const;
    [[nodiscard]] bool contains(std::string_view element) const;
    [[nodiscard]] double fallback() const { return fallback_; }
    [[nodiscard]] std::size_t size() const { return radii_.size(); }
    /// Sets (or replaces) one entry. \throw InvalidInput for an empty symbol or a radius ≤ 0.
    void set(std::string_view element, double radius);

private:
    std::map<std::string, double> radii_;
    double fallback_ = 1.80;
};

/// XYZR (the MSMS convention): one atom per line, `x y z r`; blank lines and '#' comments are
/// skipped. Elements are left empty.
[[nodiscard]] std::vector<Atom> read_xyzr(const std::filesystem::path& path);

/// PQR: ATOM and HETATM records whose last five whitespace-separated fields are
/// `x y z charge radius` (with or without a chain identifier); other records are skipped. The
/// element is the first letter of the atom name (the third field) after leading digits, which is
/// informative only: the radius comes from the file.
[[nodiscard]] std::vector<Atom> read_pqr(const std::filesystem::path& path);

/// Weighted points as CGAL's skin-surface examples store them: `x y z w` per line, w the weight
/// (squared radius; it may be negative). Blank lines and '#' comments are skipped.
[[nodiscard]] std::vector<WeightedPoint> read_weighted_points(const std::filesystem::path& path);

/// What the structure readers keep (specs/skin-surfaces.md §6.4).
struct MoleculeReadOptions {
    bool keep_water = false;      ///< waters (HOH, WAT, DOD, ...) are skipped unless set
    bool keep_hydrogens = true;   ///< H and D atoms; clear to mesh heavy atoms only
    /// Atoms with an alternate location are kept when it is blank or this one ('A' by default;
    /// the first alternate location of a residue when the file has no 'A').
    char altloc = 'A';
    int model = 1;                ///< the model (1-based, in file order) of a multi-model file
};

/// What a structure reader skipped.
struct MoleculeReadReport {
    std::string format;               ///< "pdb", "mmcif", "pqr", "xyzr"
    std::size_t models = 0;           ///< models in the file
    std::size_t skipped_water = 0;
    std::size_t skipped_hydrogens = 0;
    std::size_t skipped_altloc = 0;
    std::size_t unknown_radius = 0;   ///< atoms given the table's fallback radius
};

/// PDB (fixed columns) and mmCIF files through gemmi, radii from `radii` by element (gemmi
/// infers a blank element from the atom name). Coordinates are checked first by our own scan
/// of the PDB records, so a malformed ATOM/HETATM record is reported with its line: gemmi's
/// own errors give a line only for some problems (a record too short); an mmCIF syntax error
/// keeps gemmi's "line N" message, and a non-numeric mmCIF coordinate is named by atom serial.
/// 	hrow IoError "<file>:<line>: <problem>", or "<file>: ..." for file-level problems (no
///        atom left, a model that does not exist).
[[nodiscard]] std::vector<Atom> read_pdb(const std::filesystem::path& path, const RadiusTable& radii,
                                         const MoleculeReadOptions& options = {}, MoleculeReadReport* report = nullptr);
[[nodiscard]] std::vector<Atom> read_mmcif(const std::filesystem::path& path, const RadiusTable& radii,
                                           const MoleculeReadOptions& options = {}, MoleculeReadReport* report = nullptr);

/// Any molecule file by its extension: .pdb/.ent (PDB), .cif/.mmcif (mmCIF), .pqr (radii from
/// the file), .xyzr (radii from the file). 	hrow IoError for another extension.
[[nodiscard]] std::vector<Atom> read_molecule(const std::filesystem::path& path, const RadiusTable& radii,
                                              const MoleculeReadOptions& options = {}, MoleculeReadReport* report = nullptr);

/// The skin's ball set for atoms shrunk by s ∈ (0, 1]: (z_i, r_i²/s).
/// \throw InvalidInput when s is outside (0, 1].
[[nodiscard]] std::vector<WeightedPoint> skin_weights(const std::vector<Atom>& atoms, double s);

}  // namespace dynmesh
