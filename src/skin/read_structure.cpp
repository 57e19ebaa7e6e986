// PDB and mmCIF molecules through gemmi, with our own scan of the PDB coordinate columns so
// that a malformed record is named by its line.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <string>
#include <string_view>
#include <utility>

#include <gemmi/cif.hpp>
#include <gemmi/mmcif.hpp>
#include <gemmi/model.hpp>
#include <gemmi/pdb.hpp>

#include "../io/io_common.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/io/input_file.hpp"
#include "dynmesh/skin/molecule.hpp"

namespace dynmesh {

namespace {

/// Where each (model, serial) atom record of a PDB file is, after checking its coordinate
/// columns 31–54 (three numbers of 8 columns each).
std::map<std::pair<int, int>, std::size_t> scan_pdb_records(const std::string& data, const detail::FileContext& ctx) {
    std::map<std::pair<int, int>, std::size_t> lines;
    detail::LineReader reader(data);
    std::string_view line;
    int model = 1;
    bool seen_atoms = false;
    while (reader.next(line)) {
        if (line.starts_with("ENDMDL")) {
            if (seen_atoms) ++model;
            seen_atoms = false;
            continue;
        }
        if (!line.starts_with("ATOM  ") && !line.starts_with("HETATM")) continue;
        if (line.size() < 54)
            ctx.fail_line(reader.line_number(), "an ATOM/HETATM record needs coordinates in columns 31-54, the line has " +
                                                    std::to_string(line.size()) + " columns");
        static const char* const kAxis[3] = {"x", "y", "z"};
        for (int k = 0; k < 3; ++k) {
            std::string_view field = line.substr(30 + 8 * std::size_t(k), 8);
            while (!field.empty() && field.front() == ' ') field.remove_prefix(1);
            while (!field.empty() && field.back() == ' ') field.remove_suffix(1);
            double v = 0;
            if (!detail::parse_double(field, v) || !std::isfinite(v))
                ctx.fail_line(reader.line_number(), std::string("the ") + kAxis[k] + " coordinate " + detail::quote_text(field) +
                                                        " (columns " + std::to_string(31 + 8 * k) + "-" +
                                                        std::to_string(38 + 8 * k) + ") is not a number");
        }
        int serial = 0;
        std::string_view s = line.substr(6, 5);
        while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
        for (char c : s)
            if (std::isdigit(static_cast<unsigned char>(c))) serial = serial * 10 + (c - '0');
        lines.emplace(std::pair{model, serial}, reader.line_number());
        seen_atoms = true;
    }
    return lines;
}

/// Turns gemmi's model into atoms under the options.
std::vector<Atom> atoms_of(const gemmi::Structure& st, const detail::FileContext& ctx, const RadiusTable& radii,
                           const MoleculeReadOptions& options, MoleculeReadReport& report,
                           const std::map<std::pair<int, int>, std::size_t>* lines) {
    report.models = st.models.size();
    if (st.models.empty()) ctx.fail("no ATOM or HETATM record in the file");
    if (options.model < 1 || std::size_t(options.model) > st.models.size())
        ctx.fail("the file has " + std::to_string(st.models.size()) + " model(s); model " + std::to_string(options.model) +
                 " does not exist");
    const gemmi::Model& model = st.models[std::size_t(options.model - 1)];
    std::vector<Atom> atoms;
    for (const gemmi::Chain& chain : model.chains)
        for (const gemmi::Residue& res : chain.residues) {
            if (res.is_water() && !options.keep_water) {
                report.skipped_water += res.atoms.size();
                continue;
            }
            // The alternate location kept in this residue: the option's, else the first seen.
            char keep = 0;
            for (const gemmi::Atom& a : res.atoms)
                if (a.altloc == options.altloc) keep = a.altloc;
            if (!keep)
                for (const gemmi::Atom& a : res.atoms)
                    if (a.altloc) {
                        keep = a.altloc;
                        break;
                    }
            for (const gemmi::Atom& a : res.atoms) {
                if (a.altloc && a.altloc != keep) {
                    ++report.skipped_altloc;
                    continue;
                }
                if (a.is_hydrogen() && !options.keep_hydrogens) {
                    ++report.skipped_hydrogens;
                    continue;
                }
                std::size_t line = 0;
                if (lines) {
                    const auto it = lines->find({options.model, a.serial});
                    if (it != lines->end()) line = it->second;
                }
                if (!std::isfinite(a.pos.x) || !std::isfinite(a.pos.y) || !std::isfinite(a.pos.z))
                    ctx.fail("atom " + std::to_string(a.serial) + " (" + a.name + " of " + res.name +
                             "): a coordinate is not a number");
                std::string element = a.element == gemmi::El::X ? std::string() : std::string(a.element.uname());
                if (element.empty() || !radii.contains(element)) ++report.unknown_radius;
                atoms.push_back({{a.pos.x, a.pos.y, a.pos.z}, radii.radius(element), element, line});
            }
        }
    if (atoms.empty()) ctx.fail("no atom left (after skipping waters, hydrogens and alternate locations)");
    return atoms;
}

/// The report a reader fills: the caller's, or `local`, emptied and named with the format.
MoleculeReadReport& fresh_report(MoleculeReadReport* report, MoleculeReadReport& local, const char* format) {
    MoleculeReadReport& r = report ? *report : local;
    r = {};
    r.format = format;
    return r;
}

}  // namespace

std::vector<Atom> read_pdb(const std::filesystem::path& path, const RadiusTable& radii, const MoleculeReadOptions& options,
                           MoleculeReadReport* report) {
    const detail::FileContext ctx(path);
    const std::string data = detail::load_file(path, ctx, kMaxScriptFileBytes);
    const auto lines = scan_pdb_records(data, ctx);
    MoleculeReadReport local;
    MoleculeReadReport& r = fresh_report(report, local, "pdb");
    gemmi::Structure st;
    try {
        st = gemmi::read_pdb_string(data, path.filename().string());
    } catch (const std::exception& e) {
        std::string msg = e.what();
        // gemmi: "Problem in line N: ..."; keep its line in our format.
        const std::string prefix = "Problem in line ";
        if (msg.starts_with(prefix)) {
            const std::size_t colon = msg.find(':');
            const std::size_t n = std::stoul(msg.substr(prefix.size()));
            std::string rest = colon == std::string::npos ? msg : msg.substr(colon + 2);
            rest = rest.substr(0, rest.find('\n'));
            ctx.fail_line(n, rest);
        }
        ctx.fail(msg.substr(0, msg.find('\n')));
    }
    return atoms_of(st, ctx, radii, options, r, &lines);
}

std::vector<Atom> read_mmcif(const std::filesystem::path& path, const RadiusTable& radii, const MoleculeReadOptions& options,
                             MoleculeReadReport* report) {
    const detail::FileContext ctx(path);
    const std::string data = detail::load_file(path, ctx, kMaxScriptFileBytes);
    MoleculeReadReport local;
    MoleculeReadReport& r = fresh_report(report, local, "mmcif");
    gemmi::Structure st;
    try {
        const gemmi::cif::Document doc = gemmi::cif::read_memory(data.data(), data.size(), path.filename().string().c_str());
        if (doc.blocks.empty()) ctx.fail("no data block in the file");
        st = gemmi::make_structure_from_block(doc.blocks[0]);
    } catch (const IoError&) {
        throw;
    } catch (const std::exception& e) {
        const std::string msg = e.what();
        ctx.fail(msg.substr(0, msg.find('\n')));
    }
    return atoms_of(st, ctx, radii, options, r, nullptr);
}

std::vector<Atom> read_molecule(const std::filesystem::path& path, const RadiusTable& radii, const MoleculeReadOptions& options,
                                MoleculeReadReport* report) {
    const std::string ext = detail::lower_extension(path);
    if (ext == ".pdb" || ext == ".ent") return read_pdb(path, radii, options, report);
    if (ext == ".cif" || ext == ".mmcif") return read_mmcif(path, radii, options, report);
    MoleculeReadReport local;
    if (ext == ".pqr") {
        fresh_report(report, local, "pqr");
        return read_pqr(path);
    }
    if (ext == ".xyzr") {
        fresh_report(report, local, "xyzr");
        return read_xyzr(path);
    }
    const detail::FileContext ctx(path);
    ctx.fail("unknown molecule format " + detail::quote_text(ext) + " (expected .pdb, .ent, .cif, .mmcif, .pqr or .xyzr)");
}

}  // namespace dynmesh
