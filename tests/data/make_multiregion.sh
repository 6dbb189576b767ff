#!/bin/sh
# Writes the multi-subdomain medit test meshes with the tools that make them in practice:
#   ff_inclusion.mesh      FreeFem++ buildmesh: unit square (labels 1-4) with a disk inclusion
#                          (label 5); two subdomains (FreeFem region numbers), Edges with labels
#   ff_disk_inclusion.mesh FreeFem++ buildmesh: the unit disk (label 1) with an off-centre disk
#                          inclusion of radius 0.4 (label 2): curved outer boundary and interface
#   gmsh_two_regions.mesh  gmsh -2 -format mesh: [0,2]x[0,1] cut by a two-segment interface
#                          into two surfaces; Dimension 3, z = 0; gmsh writes the elementary
#                          entity tags as refs (curves 7 and 8 on the interface, surfaces 1 and 2)
#   gmsh_disk_three.mesh   gmsh -2 -format mesh, physical tags as refs (Mesh.SaveElementTagType
#                          2): the unit disk (four arcs, ref 10) cut along y = 0 (ref 20) into
#                          an upper (1) and a lower (3) half, and the square [-0.3,0.3]x[0.2,0.6]
#                          (ref 30) in the upper half as a third surface (2): three surfaces
#                          sharing curves, a curved outer boundary, polygonal interfaces
# Run from anywhere: sh tests/data/make_multiregion.sh (needs FreeFem++ and gmsh).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/inclusion.edp" <<'EDP'
border a(t=0,1){x=t; y=0; label=1;}
border b(t=0,1){x=1; y=t; label=2;}
border c(t=0,1){x=1-t; y=1; label=3;}
border d(t=0,1){x=0; y=1-t; label=4;}
border e(t=0,2*pi){x=0.5+0.25*cos(t); y=0.5+0.25*sin(t); label=5;}
mesh Th = buildmesh(a(12)+b(12)+c(12)+d(12)+e(40));
savemesh(Th, "ff_inclusion.mesh");
EDP
(cd "$tmp" && FreeFem++ -nw inclusion.edp > /dev/null)
cp "$tmp/ff_inclusion.mesh" "$here/ff_inclusion.mesh"
cat > "$tmp/disk_inclusion.edp" <<'EDP'
border a(t=0,2*pi){x=cos(t); y=sin(t); label=1;}
border b(t=0,2*pi){x=0.2+0.4*cos(t); y=0.1+0.4*sin(t); label=2;}
mesh Th = buildmesh(a(48)+b(24));
savemesh(Th, "ff_disk_inclusion.mesh");
EDP
(cd "$tmp" && FreeFem++ -nw disk_inclusion.edp > /dev/null)
cp "$tmp/ff_disk_inclusion.mesh" "$here/ff_disk_inclusion.mesh"
cat > "$tmp/two.geo" <<'GEO'
lc = 0.1;
Point(1) = {0, 0, 0, lc}; Point(2) = {1, 0, 0, lc}; Point(3) = {2, 0, 0, lc};
Point(4) = {2, 1, 0, lc}; Point(5) = {1.2, 1, 0, lc}; Point(6) = {0, 1, 0, lc};
Point(7) = {0.8, 0.5, 0, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6}; Line(6) = {6, 1};
Line(7) = {2, 7}; Line(8) = {7, 5};
Curve Loop(1) = {1, 7, 8, 5, 6}; Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -8, -7}; Plane Surface(2) = {2};
Physical Curve(1) = {1, 2}; Physical Curve(2) = {3}; Physical Curve(3) = {4, 5}; Physical Curve(4) = {6};
Physical Curve(7) = {7, 8};
Physical Surface(10) = {1}; Physical Surface(20) = {2};
GEO
gmsh -2 -format mesh "$tmp/two.geo" -o "$here/gmsh_two_regions.mesh" > /dev/null
cat > "$tmp/disk_three.geo" <<'GEO'
lc = 0.1;
Point(1) = {0, 0, 0, lc};
Point(2) = {1, 0, 0, lc}; Point(3) = {0, 1, 0, lc}; Point(4) = {-1, 0, 0, lc}; Point(5) = {0, -1, 0, lc};
Point(6) = {-0.3, 0.2, 0, lc}; Point(7) = {0.3, 0.2, 0, lc}; Point(8) = {0.3, 0.6, 0, lc}; Point(9) = {-0.3, 0.6, 0, lc};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Line(5) = {4, 2};
Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 9}; Line(9) = {9, 6};
Curve Loop(1) = {1, 2, 5}; Curve Loop(2) = {6, 7, 8, 9}; Plane Surface(1) = {1, 2};
Plane Surface(2) = {2};
Curve Loop(3) = {3, 4, -5}; Plane Surface(3) = {3};
Physical Curve(10) = {1, 2, 3, 4}; Physical Curve(20) = {5}; Physical Curve(30) = {6, 7, 8, 9};
Physical Surface(1) = {1}; Physical Surface(2) = {2}; Physical Surface(3) = {3};
GEO
gmsh -2 -format mesh -setnumber Mesh.SaveElementTagType 2 "$tmp/disk_three.geo" \
  -o "$here/gmsh_disk_three.mesh" > /dev/null
echo "wrote $here/ff_inclusion.mesh $here/ff_disk_inclusion.mesh $here/gmsh_two_regions.mesh" \
  "$here/gmsh_disk_three.mesh"
