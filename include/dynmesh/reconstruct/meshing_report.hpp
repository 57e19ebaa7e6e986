#pragma once
/// \file What every sample-to-mesh routine reports.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace dynmesh {

struct SampleMeshingReport {
    std::size_t samples = 0;         ///< input size
    std::size_t vertices_used = 0;   ///< samples that are mesh vertices
    std::size_t unused_samples = 0;  ///< samples in no output triangle
    std::size_t facets = 0;          ///< triangles of the result
    /// Input index of each mesh vertex: vertex v is samples[vertex_sample[v.idx()]]. Strictly
    /// increasing, since vertices keep the order of the samples.
    std::vector<std::uint32_t> vertex_sample;
    double seconds = 0;  ///< wall-clock time of the whole call
};

}  // namespace dynmesh
