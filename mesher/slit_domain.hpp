#pragma once
/// Meshing a domain with slits (core/domain.hpp: the zero-width gaps of its loops).
///
/// Placement and connection (paper §3–4) work on a domain whose loops are simple, so a domain
/// with slits is cut, for meshing only: from each slit tip straight ahead (its last segment
/// extended) to the first loop it meets. A cut that meets the tip's own loop splits the piece in
/// two; one that meets another loop (a free slit's first tip) joins the two loops, and the next
/// tip then splits. Each cut is discretized once, into round(metric length) pieces of equal
/// metric length; its points are fixed and each of its segments kept as one edge, so both sides
/// get the same vertices. The pieces are meshed alone and glued at the cut points only: the two
/// lips of a slit, in different pieces, keep distinct vertices at the same coordinates, the tip
/// is one vertex, and no mesh edge crosses the slit. The cut lines are no boundary of the result
/// (its edges are interior edges), but the mesh has a line of edges along each of them.
#include "ablmg/core/domain.hpp"
#include "ablmg/core/metric_field.hpp"
#include "ablmg/mesher/mesher.hpp"

#include <climits>
#include <vector>

namespace ablmg::mesher {

/// The tag of cut segments in SlitPieces::pieces (no tag of the result).
constexpr int kSlitCutTag = INT_MIN + 2;

struct SlitPieces {
  std::vector<Domain> pieces;           ///< valid Domains without slits; cut segments tagged kSlitCutTag
  std::vector<std::vector<Vec2>> cuts;  ///< each cut's points, tip first, ends included
};

/// Cuts `domain` at its slits (see above), the cuts discretized in `metric`. A domain without
/// slits comes back as its one piece. Throws InputError "domain: ..." naming the tip when a tip's
/// extension meets no loop, or when the cuts leave a piece with a gap (a slit attached to a hole
/// whose extension meets another loop).
SlitPieces cutAtSlits(const Domain& domain, const MetricField& metric);

/// meshDomain for a domain with slits (meshDomain calls it when domain.hasSlits()): the pieces
/// of cutAtSlits meshed with `options` and glued. Valid; boundary edges carry the loops' tags.
MeshResult meshSlitDomain(const Domain& domain, const MetricField& metric, const MeshOptions& options);

}  // namespace ablmg::mesher
