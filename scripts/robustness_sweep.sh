#!/usr/bin/env bash
# Robustness sweep: `ablmg adapt` on the problem library away from its defaults, `ablmg mesh` /
# `remesh` on other metrics and domains, medit files as gmsh / FreeFem++ / MMG write them, and
# hostile inputs. Every run is small (≤ a few 10⁴ vertices). Prints one line per case:
#   ok|FAIL  part  case  (exit code, seconds, and what was checked)
# and exits non-zero if any case failed. Usage:
#   bash scripts/robustness_sweep.sh [adapt|mesh|files|hostile ...]   (default: all parts)
# Env: ABLMG (default build/bin/ablmg), OUT (default /tmp/ablmg_sweep), TIMEOUT (s, default 300),
#      MMG (mmg2d binary; the MMG cases are skipped without it).
set -u
cd "$(dirname "$0")/.."
ABLMG=${ABLMG:-$PWD/build/bin/ablmg}
OUT=${OUT:-/tmp/ablmg_sweep}
TIMEOUT=${TIMEOUT:-300}
MMG=${MMG:-}
mkdir -p "$OUT"
fails=0
report() {  # report STATUS PART CASE DETAIL
  printf '%-4s %-7s %-40s %s\n' "$1" "$2" "$3" "$4"
  [[ $1 == ok ]] || fails=$((fails + 1))
}
run() {  # run NAME CMD... : stdout+stderr in $OUT/NAME.log; sets rc, secs
  local name=$1; shift
  local t0=$(date +%s.%N)
  timeout "$TIMEOUT" "$@" > "$OUT/$name.log" 2>&1
  rc=$?
  secs=$(printf '%.1f' "$(echo "$(date +%s.%N) - $t0" | bc)")
}

# --- 1. adapt on the library with other parameters -------------------------------------------
# A case passes when the run exits 0, its errors fall from the first to the last cycle and the
# L2 and H1 rates of its last cycles are below -0.3 and -0.15 (optimal -1 and -0.5).
adapt_case() {  # adapt_case NAME ARGS...
  local name=$1; shift
  run "adapt_$name" "$ABLMG" adapt "$@" --vtu off -v 0 --out-dir "$OUT/adapt_$name"
  local log=$OUT/adapt_$name.log
  if [[ $rc -ne 0 ]]; then report FAIL adapt "$name" "exit $rc after ${secs}s: $(grep -m1 -i 'error' "$log" | cut -c1-120)"; return; fi
  local rates=$(grep -m1 '^Rates' "$log" | sed 's/.*H1 -0.5)://')
  local l2=$(echo "$rates" | awk '{print $2}') h1=$(echo "$rates" | awk '{print $4}')
  local falls=$(grep -c 'Errors decrease from the first to the last cycle: yes' "$log")
  if [[ -z $l2 ]]; then report ok adapt "$name" "${secs}s, no exact solution"; return; fi
  local last=$(grep '^Cycle' "$log" | tail -1 | grep -o 'L2=[0-9.e+-]*' | cut -d= -f2)
  if awk -v e="$last" 'BEGIN{exit !(e < 1e-12)}'; then report ok adapt "$name" "${secs}s exact (L2 $last)"; return; fi
  if [[ $l2 == n/a ]]; then report ok adapt "$name" "${secs}s one size (no rate), errors fall: $falls"; return; fi
  if [[ $falls -eq 1 ]] && awk -v a="$l2" -v b="$h1" 'BEGIN{exit !(a < -0.3 && b < -0.15)}'; then
    report ok adapt "$name" "${secs}s L2 $l2 H1 $h1"
  else
    report FAIL adapt "$name" "${secs}s L2 rate $l2, H1 rate $h1, errors fall: $falls"
  fi
}
part_adapt() {
  local V="--vertices 4000"
  adapt_case wavefront_centre_inside --problem wavefront --param xc=0.5 --param yc=0.5 --param r0=0.25 $V
  adapt_case wavefront_centre_vertex --problem wavefront --param xc=0.5 --param yc=0.5 --param r0=0 $V
  adapt_case wavefront_centre_corner --problem wavefront --param xc=0 --param yc=0 --param r0=0.5 $V
  adapt_case wavefront_alpha_1000 --problem wavefront --param alpha=1000 $V
  adapt_case wavefront_alpha_1 --problem wavefront --param alpha=1 $V
  adapt_case wavefront_outside --problem wavefront --param xc=1.5 --param yc=0.5 --param r0=0.7 $V
  adapt_case peak_corner --problem peak --param xc=0 --param yc=0 $V
  adapt_case peak_edge --problem peak --param xc=0.5 --param yc=0 $V
  adapt_case peak_outside --problem peak --param xc=1.2 --param yc=0.5 $V
  adapt_case peak_alpha_1e5 --problem peak --param alpha=1e5 $V
  adapt_case peak_alpha_1 --problem peak --param alpha=1 $V
  for e in 0.1 0.03 0.003 0.001; do adapt_case tanhlayer_eps_$e --problem tanhlayer --param epsilon=$e $V; done
  for w in 1.01 1.25 1.5 1.75 1.9 1.99 2; do
    adapt_case reentrant_omega_${w}pi --problem reentrant --param omega=$(echo "$w * 3.141592653589793" | bc -l) $V
  done
  adapt_case reentrant_omega_nearly_2pi --problem reentrant --param omega=6.2831 $V
  adapt_case linesing_alpha_1.5 --problem linesing --param alpha=1.5 $V
  adapt_case linesing_alpha_4 --problem linesing --param alpha=4 $V
  adapt_case linesing_beta_0 --problem linesing --param beta=0 $V
  adapt_case linesing_beta_2 --problem linesing --param beta=2 $V
  adapt_case multiple_eps_1e-3 --problem multiple --param epsilon=0.001 $V
  adapt_case multiple_sharp --problem multiple --param alpha_p=1e4 --param alpha_w=1000 $V
  adapt_case multiple_moved --problem multiple --param xp=0.5 --param yp=0.5 --param xw=-0.5 --param yw=0.5 --param r0=0.3 $V
  for p in peak lshape linesing; do
    adapt_case ${p}_p1_h1 --problem $p --p 1 --norm h1 $V
    adapt_case ${p}_pinf --problem $p --p inf $V
  done
  adapt_case smooth_small --problem smooth --vertices 200
  adapt_case sine_large --problem sine --vertices 30000
  adapt_case wavefront_stop_h1 --problem wavefront --vertices 30000 --stop-h1 0.05
  adapt_case peak_stop_l2 --problem peak --vertices 30000 --stop-l2 1e-5
  adapt_case lshape_targets --problem lshape --target-vertices 500,1000,2000,4000
  adapt_case tanhlayer_hmin --problem tanhlayer --hmin 1e-3 --hmax 0.1 --max-aniso 100 $V
  adapt_case peak_hgrad_off --problem peak --hgrad -1 $V
  adapt_case wavefront_growth_4 --problem wavefront --growth 4 --passes 1 $V
  adapt_case linear_tiny --problem linear --vertices 50
}

# --- 2. mesh / remesh on other metrics and domains ------------------------------------------------
# A case passes when the run exits 0 and `ablmg stats` finds the mesh valid; the stats line of
# the share of edges in [1/sqrt2, sqrt2] is printed.
mesh_case() {  # mesh_case NAME JSON
  local name=$1 cfg=$OUT/mesh_$1.json
  echo "$2" > "$cfg"
  run "mesh_$name" "$ABLMG" mesh "$cfg" -o "$OUT/mesh_$name.mesh" -v 0
  local log=$OUT/mesh_$name.log
  if [[ $rc -ne 0 ]]; then report FAIL mesh "$name" "exit $rc after ${secs}s: $(tail -1 "$log" | cut -c1-150)"; return; fi
  "$ABLMG" stats "$OUT/mesh_$name.mesh" --sol "$OUT/mesh_$name.sol" > "$OUT/mesh_$name.stats" 2>&1
  if grep -q 'valid: yes' "$OUT/mesh_$name.stats"; then
    report ok mesh "$name" "${secs}s $(grep -o '[0-9]* vertices' "$OUT/mesh_$name.stats"), $(grep -o 'l in \[1/sqrt2, sqrt2\]: [0-9.]*%' "$OUT/mesh_$name.stats")"
  else
    report FAIL mesh "$name" "${secs}s invalid mesh: $(grep -m1 valid "$OUT/mesh_$name.stats")"
  fi
}
part_mesh() {
  local sq='"domain": {"rectangle": [0, 0, 1, 1]}'
  mesh_case aniso_1e5_rotating "{$sq, \"metric\": {\"h1\": \"0.5\", \"h2\": \"5e-6+0.02*abs(x-0.5)\", \"theta\": \"3*y\"}}"
  mesh_case aniso_1e4_layer "{$sq, \"metric\": {\"h1\": \"0.2\", \"h2\": \"2e-5+0.5*abs(y-0.5)\", \"theta\": \"0\"}}"
  mesh_case size_1e-3 "{$sq, \"metric\": {\"h\": \"0.004\"}}"
  mesh_case size_1e3 "{$sq, \"metric\": {\"h\": \"1e3\"}}"
  mesh_case fast_varying "{$sq, \"metric\": {\"h\": \"0.01+0.05*(1+sin(60*x)*sin(60*y))\"}}"
  mesh_case size_jump "{$sq, \"metric\": {\"h\": \"x<0.5 ? 0.005 : 0.1\"}}"
  mesh_case many_holes "{\"domain\": {\"loops\": [[[0,0],[3,0],[3,3],[0,3]], $(for i in 0 1 2 3 4; do for j in 0 1 2 3 4; do x=$(echo "0.3+$i*0.55" | bc -l); y=$(echo "0.3+$j*0.55" | bc -l); printf '[[%.4f,%.4f],[%.4f,%.4f],[%.4f,%.4f]],' $x $y $(echo "$x+0.3" | bc -l) $y $x $(echo "$y+0.3" | bc -l); done; done | sed 's/,$//')]}, \"metric\": {\"h\": \"0.05\"}}"
  mesh_case sliver_1e-3 "{\"domain\": {\"rectangle\": [0, 0, 1, 0.001]}, \"metric\": {\"h\": \"0.05\"}}"
  mesh_case sliver_wedge "{\"domain\": {\"loops\": [[[0,0],[1,0],[1,0.01]]]}, \"metric\": {\"h\": \"0.02\"}}"
  mesh_case long_segments "{\"domain\": {\"loops\": [[[0,0],[100,0],[100,1],[0,1]]]}, \"metric\": {\"h\": \"0.1\"}}"
  mesh_case short_segments "{\"domain\": {\"loops\": [$(/usr/bin/python3 -c "import math; print('[' + ','.join('[%.12g,%.12g]' % (math.cos(2*math.pi*k/2000), math.sin(2*math.pi*k/2000)) for k in range(2000)) + ']')")]}, \"metric\": {\"h\": \"0.1\"}}"
  mesh_case comb "{\"domain\": {\"loops\": [[[0,0],[2,0],[2,1],[1.9,1],[1.9,0.1],[1.8,0.1],[1.8,1],[1.7,1],[1.7,0.1],[1.6,0.1],[1.6,1],[0,1]]]}, \"metric\": {\"h\": \"0.03\"}}"
  mesh_case spiral_aniso "{\"domain\": {\"disk\": {\"center\": [0, 0], \"radius\": 1}}, \"metric\": {\"h1\": \"0.1\", \"h2\": \"0.002+0.05*abs(sqrt(x^2+y^2)-0.5)\", \"theta\": \"atan2(y,x)+pi/2\"}}"
  mesh_case far_offset "{\"domain\": {\"rectangle\": [1e6, 1e6, 1000001, 1000001]}, \"metric\": {\"h\": \"0.05\"}}"
  mesh_case far_offset_1e12 "{\"domain\": {\"loops\": [[[1e12,1e12],[1000000000001,1e12],[1000000000001,1000000000001],[1e12,1000000000001]], [[1000000000000.3,1000000000000.3],[1000000000000.6,1000000000000.3],[1000000000000.6,1000000000000.6]]]}, \"metric\": {\"h\": \"0.05\"}}"
  mesh_case tiny_domain "{\"domain\": {\"rectangle\": [0, 0, 1e-6, 1e-6]}, \"metric\": {\"h\": \"5e-8\"}}"
  mesh_case huge_domain "{\"domain\": {\"rectangle\": [0, 0, 1e6, 1e6]}, \"metric\": {\"h\": \"5e4\"}}"
}

# --- 3. medit files as gmsh, FreeFem++ and MMG write them ----------------------------------------
# A case passes when `remesh` exits 0 and scripts/check_regions.py finds every triangle
# reference kept by region (its area within 1 %, or exactly with -nosurf).
remesh_case() {  # remesh_case NAME IN.mesh [--exact] ARGS...
  local name=$1 in=$2; shift 2
  local exact=""
  if [[ ${1:-} == --exact ]]; then exact=--exact; shift; fi
  run "remesh_$name" "$ABLMG" remesh -in "$in" -out "$OUT/remesh_$name.mesh" -v 0 "$@"
  local log=$OUT/remesh_$name.log
  if [[ $rc -ne 0 ]]; then report FAIL files "$name" "exit $rc after ${secs}s: $(tail -1 "$log" | cut -c1-150)"; return; fi
  local chk
  chk=$(/usr/bin/python3 scripts/check_regions.py "$in" "$OUT/remesh_$name.mesh" $exact 2>&1)
  if [[ $chk == ok* ]]; then report ok files "$name" "${secs}s $chk"; else report FAIL files "$name" "${secs}s $chk"; fi
}
part_files() {
  local d=$OUT/files
  mkdir -p "$d"
  # gmsh: three regions (a disk, a rectangle with a hole, the rest), Dimension 3 with z = 0
  cat > "$d/regions.geo" <<'GEO'
SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 2, 1};
Disk(2) = {0.6, 0.5, 0, 0.25};
Rectangle(3) = {1.3, 0.2, 0, 0.4, 0.6};
Disk(4) = {1.5, 0.5, 0, 0.1};
BooleanFragments{ Surface{1}; Delete; }{ Surface{2,3}; Delete; }
Recursive Delete { Surface{4}; }
Mesh.CharacteristicLengthMax = 0.08;
GEO
  if command -v gmsh > /dev/null; then
    gmsh "$d/regions.geo" -2 -format mesh -o "$d/gmsh.mesh" > /dev/null 2>&1
    remesh_case gmsh_regions "$d/gmsh.mesh" -hsiz 0.03
    remesh_case gmsh_regions_nosurf "$d/gmsh.mesh" --exact -hsiz 0.03 -nosurf
    sed 's/$/\r/' "$d/gmsh.mesh" > "$d/gmsh_crlf.mesh"
    remesh_case gmsh_crlf "$d/gmsh_crlf.mesh" -hsiz 0.03
    { echo "# written by gmsh"; sed 's/^ *Vertices/Vertices # the points/' "$d/gmsh.mesh" | tr ' ' '\t'; } > "$d/gmsh_odd.mesh"
    remesh_case gmsh_comments_tabs "$d/gmsh_odd.mesh" -hsiz 0.03
  fi
  # FreeFem++: two regions and a hole, its own trailing sections, a .sol with a size and a tensor field
  cat > "$d/ff.edp" <<'EDP'
border a(t=0,1){x=2*t; y=0; label=1;}
border b(t=0,1){x=2; y=t; label=2;}
border c(t=0,1){x=2-2*t; y=1; label=3;}
border d(t=0,1){x=0; y=1-t; label=4;}
border e(t=0,2*pi){x=0.6+0.25*cos(t); y=0.5+0.25*sin(t); label=5;}
border h(t=0,2*pi){x=1.5+0.1*cos(t); y=0.5-0.1*sin(t); label=6;}
mesh Th = buildmesh(a(30)+b(15)+c(30)+d(15)+e(30)+h(12));
fespace Vh(Th,P1);
Vh m11 = 1/(0.05^2), m12 = 0, m22 = 1/(0.01+0.05*abs(y-0.5))^2;
savemesh(Th, "ff.mesh");
{ ofstream f("ff.sol"); f << "MeshVersionFormatted 1\nDimension 2\nSolAtVertices\n" << Th.nv << "\n2 1 3\n";
  for (int i = 0; i < Th.nv; i++) f << 0.05 << " " << m11[][i] << " " << m12[][i] << " " << m22[][i] << "\n";
  f << "End\n"; }
EDP
  if command -v FreeFem++ > /dev/null; then
    (cd "$d" && FreeFem++ -nw ff.edp > ff.log 2>&1)
    remesh_case freefem_tensor_field "$d/ff.mesh" -sol "$d/ff.sol"
    remesh_case freefem_size_field "$d/ff.mesh" -sol "$d/ff.sol" -met-field 1
    # MMG's output of the FreeFem++ mesh: Corners, RequiredVertices, its own Edges
    if [[ -n $MMG ]]; then
      cp "$d/ff.mesh" "$d/ffm.mesh"; rm -f "$d/ffm.sol"
      "$MMG" -in "$d/ffm.mesh" -hsiz 0.04 -out "$d/mmg.mesh" > "$d/mmg.log" 2>&1
      remesh_case mmg_output "$d/mmg.mesh" -hsiz 0.02
      remesh_case mmg_output_own_sol "$d/mmg.mesh" -sol "$d/mmg.sol"
    fi
  fi
}

# --- 4. hostile input ----------------------------------------------------------------------------
# A case passes when the run exits non-zero with one stderr line matching the pattern and
# leaves no output file behind.
hostile_case() {  # hostile_case NAME REGEX ARGS... (the output is $OUT/hostile_NAME.o.mesh)
  local name=$1 re=$2; shift 2
  local o=$OUT/hostile_$name.o.mesh
  rm -f "$o" "${o%.mesh}.sol"
  local log=$OUT/hostile_$name.log lines
  timeout "$TIMEOUT" "$ABLMG" "$@" > /dev/null 2> "$log"  # stderr only: the one error line
  rc=$?
  lines=$(grep -c . "$log")
  if [[ $rc -eq 0 || $rc -ge 124 ]]; then report FAIL hostile "$name" "exit $rc: $(head -1 "$log" | cut -c1-120)"
  elif [[ $lines -ne 1 ]] || ! grep -Eq -- "$re" "$log"; then report FAIL hostile "$name" "$lines lines: $(head -1 "$log" | cut -c1-140)"
  elif [[ -e $o || -e ${o%.mesh}.sol ]]; then report FAIL hostile "$name" "output left behind"
  else report ok hostile "$name" "$(cut -c1-110 "$log")"; fi
}
part_hostile() {
  local d=$OUT/hostile
  mkdir -p "$d"
  local sq="MeshVersionFormatted 2\nDimension 2\nVertices\n5\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n0.5 0.5 0\n"
  local ed="Edges\n4\n1 2 1\n2 3 2\n3 4 3\n4 1 4\n"
  local tri="Triangles\n4\n1 2 5 1\n2 3 5 1\n3 4 5 1\n4 1 5 1\n"
  printf "${sq}${ed}${tri}End\n" > "$d/sq.mesh"
  m() { printf "$2" > "$d/$1.mesh"; hostile_case "$1" "$3" remesh -in "$d/$1.mesh" -hsiz 0.2 -out "$OUT/hostile_$1.o.mesh"; }
  s() { printf "$2" > "$d/$1.sol"; hostile_case "$1" "$3" remesh -in "$d/sq.mesh" -sol "$d/$1.sol" -out "$OUT/hostile_$1.o.mesh"; }
  r() { local n=$1 re=$2; shift 2; hostile_case "$n" "$re" remesh -in "$d/sq.mesh" "$@" -out "$OUT/hostile_$n.o.mesh"; }
  m nan_coordinate "MeshVersionFormatted 2\nDimension 2\nVertices\n3\n0 0 1\nnan 0 1\n0 1 1\nTriangles\n1\n1 2 3 1\nEnd\n" 'nan_coordinate.mesh:6: vertex x coordinate is not finite'
  m inf_coordinate "MeshVersionFormatted 2\nDimension 2\nVertices\n3\n0 0 1\n1e999 0 1\n0 1 1\nTriangles\n1\n1 2 3 1\nEnd\n" 'inf_coordinate.mesh:6: vertex x coordinate is not finite'
  m truncated_in_section "${sq}${ed}Triangles\n4\n1 2 5 1\n2 3" 'truncated_in_section.mesh:[0-9]+: unexpected end of file'
  m truncated_between_sections "${sq}${ed}" 'truncated_between_sections.mesh:[0-9]+: no End keyword'
  m count_too_large "${sq}${ed}Triangles\n5\n1 2 5 1\n2 3 5 1\n3 4 5 1\n4 1 5 1\nEnd\n" 'count_too_large.mesh:[0-9]+: expected vertex index'
  m count_too_small "${sq}${ed}Triangles\n3\n1 2 5 1\n2 3 5 1\n3 4 5 1\n4 1 5 1\nEnd\n" 'count_too_small.mesh:[0-9]+: expected a section keyword, got the number'
  m duplicate_triangle_overlap "${sq}${ed}Triangles\n5\n1 2 5 1\n2 3 5 1\n3 4 5 1\n4 1 5 1\n1 2 3 1\nEnd\n" 'duplicate_triangle_overlap.mesh: invalid mesh'
  m inverted_triangle "${sq}${ed}Triangles\n4\n1 2 5 1\n2 3 5 1\n3 4 5 1\n4 1 3 1\nEnd\n" 'inverted_triangle.mesh: invalid mesh'
  m degenerate_triangle "MeshVersionFormatted 2\nDimension 2\nVertices\n4\n0 0 1\n1 0 1\n2 0 1\n0 1 1\nTriangles\n2\n1 2 3 1\n1 2 4 1\nEnd\n" 'degenerate_triangle.mesh: invalid mesh.*degenerate'
  m unused_duplicate_vertex "MeshVersionFormatted 2\nDimension 2\nVertices\n6\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n0.5 0.5 0\n0.5 0.5 0\n${tri}End\n" 'vertex 6 is used by no triangle'
  m nonplanar "MeshVersionFormatted 2\nDimension 3\nVertices\n3\n0 0 0 1\n1 0 0.5 1\n0 1 0 1\nTriangles\n1\n1 2 3 1\nEnd\n" 'nonplanar.mesh:6: vertex 2 has z = 0.5'
  m bowtie_boundary "MeshVersionFormatted 2\nDimension 2\nVertices\n4\n0 0 0\n1 1 0\n1 0 0\n0 1 0\nEdges\n4\n1 2 1\n2 3 1\n3 4 1\n4 1 1\nEnd\n" 'bowtie_boundary.mesh: edges .* cross'
  s sol_truncated "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n5\n1 3\n1 0 1\n1 0 1\n" 'sol_truncated.sol:[0-9]+: unexpected end of file'
  s sol_vector "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n5\n1 2\n1 0\n1 0\n1 0\n1 0\n1 0\nEnd\n" 'sol_vector.sol:5: solution field 1 has type 2'
  s sol_non_spd "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n5\n1 3\n1 2 1\n1 0 1\n1 0 1\n1 0 1\n1 0 1\nEnd\n" 'sol_non_spd.sol:6: tensor of vertex 1 .* not positive definite'
  s sol_aniso_1e10 "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n5\n1 3\n1e10 0 1e-10\n1 0 1\n1 0 1\n1 0 1\n1 0 1\nEnd\n" 'sol_aniso_1e10.sol:6: tensor of vertex 1.*too anisotropic'
  s sol_size_1e-300 "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n5\n1 1\n1e-300\n1\n1\n1\n1\nEnd\n" 'sol_size_1e-300.sol:6: size of vertex 1 is 1e-300'
  s sol_count "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n3\n1 1\n1\n1\n1\nEnd\n" 'sol_count.sol:4: 3 solution values but the mesh has 5'
  r size_1e-12 'asks for about [0-9.]+e\+[0-9]+ nodes' -hsiz 1e-12
  r size_negative 'hsiz must be > 0' -hsiz -1
  r hgrad_below_1 'hgrad must be > 1' -hsiz 0.2 -hgrad 0.5
  r hmin_above_hmax 'hmin < hmax' -hsiz 0.2 -hmin 0.5 -hmax 0.1
  r verbosity_99 "-v: expected an integer in" -hsiz 0.2 -v 99
  if [[ -f $OUT/files/ff.sol ]]; then  # from part files
    hostile_case field_missing 'ff.sol:5: field 3 asked for, but the file has 2 solution fields' remesh -in "$OUT/files/ff.mesh" \
      -sol "$OUT/files/ff.sol" -met-field 3 -out "$OUT/hostile_field_missing.o.mesh"
  fi
  m gmsh_msh_format '$MeshFormat\n4.1 0 8\n$EndMeshFormat\n' "gmsh_msh_format.mesh:1: expected MeshVersionFormatted, got '.meshformat' \\(a gmsh .msh file: write medit with gmsh -format mesh\\)"
  m vtu_format '<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid">\n' "vtu_format.mesh:1: .*\\(an XML file \\(VTK\\?\\): convert with meshio"
  local a=(adapt --out-dir "$OUT/hostile_adapt" -v 0 --vtu off)
  hostile_case adapt_vertices_zero '--vertices must be > 0' "${a[@]}" --problem peak --vertices 0
  hostile_case adapt_vertices_huge 'final vertices must be in \[10, 1e9\]' "${a[@]}" --problem peak --vertices 1e12
  hostile_case adapt_omega_pi "omega = 3.14.* must be in \(pi, 2 pi\]" "${a[@]}" --problem reentrant --param omega=3.14159 --vertices 400
  hostile_case adapt_epsilon_zero "epsilon = 0 must be positive" "${a[@]}" --problem tanhlayer --param epsilon=0 --vertices 400
  hostile_case adapt_linesing_alpha_1 "alpha = 1 must be > 1" "${a[@]}" --problem linesing --param alpha=1 --vertices 400
  hostile_case adapt_param_nan "--param alpha: expected a number" "${a[@]}" --problem peak --param alpha=nan --vertices 400
  hostile_case adapt_param_unknown "unknown parameter 'foo'" "${a[@]}" --problem peak --param foo=1 --vertices 400
  hostile_case adapt_p_below_1 "p must be >= 1" "${a[@]}" --problem peak --p 0.5 --vertices 400
  hostile_case adapt_shape_blend_2 "shapeBlend must be in \[0, 1\]" "${a[@]}" --problem peak --shape-blend 2 --vertices 400
  hostile_case adapt_growth_1 "growth must be in" "${a[@]}" --problem peak --growth 1 --vertices 400
  hostile_case adapt_stop_negative "stop-l2 must be a positive error" "${a[@]}" --problem peak --stop-l2 -1 --vertices 400
}

# --- main ----------------------------------------------------------------------------------------
main() {
  local parts=("$@")
  [[ ${#parts[@]} -gt 0 ]] || parts=(adapt mesh files hostile)
  for p in "${parts[@]}"; do "part_$p"; done
  echo "$fails failed"
  [[ $fails -eq 0 ]]
}
main "$@"
