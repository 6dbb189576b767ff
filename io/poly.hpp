#pragma once
/// Triangle's .poly format (Shewchuk) → Domain.
///
///   <#vertices> 2 <#attributes> <#markers 0|1>      then per vertex: id x y [attrs] [marker]
///   <#segments> <#markers 0|1>                      then per segment: id a b [marker]
///   <#holes>                                        then per hole: id x y
///   (regional attributes after the holes are ignored)
/// Ids may start at 0 or 1 (the first vertex's id decides, as in Triangle). '#' comments.
///
/// Segments are assembled into closed loops (every vertex used must end exactly two
/// segments); the loop of largest area is the outer loop; a loop containing a listed hole
/// point is a hole. Segment boundary markers become the segment tags (1 when absent or 0).
/// Slits (Domain::withSlit), two ways: a chain of segments hanging off a loop vertex and
/// ending at a vertex of no other segment (its tip; both lips get the chain's marker), or a
/// free chain inside the domain (both ends tips); or, as in medit, a zero-width gap: distinct
/// vertices at the same coordinates, the loop running along the slit and back (each lip its
/// own marker; a free slit is then a loop of zero area, which needs no hole point).
/// Errors (ablmg::InputError) name file:line and the vertex/segment: an open loop ("boundary
/// is not closed at vertex 4"), a branching vertex, indices out of range, non-finite
/// coordinates, a `.poly` with 0 vertices (separate .node file, not supported), an inner loop
/// that contains no hole point (interior constraint loops are not supported yet).
#include "ablmg/core/domain.hpp"

#include <string>

namespace ablmg::io {

Domain readPoly(const std::string& path);
/// Same, from text in memory; `name` is used in messages.
Domain parsePoly(const std::string& text, const std::string& name);

}  // namespace ablmg::io
