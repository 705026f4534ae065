#!/bin/bash
# geotex segment --tiles N --tile-dir DIR --pass P: a tiled segmentation run as separate jobs,
# a pass at a time, its tiles spread over shards run by GNU parallel (issue 21 item 3,
# docs/tiles.md). The joined result is the one-process tiled run's, byte for byte (PLY and
# JSON report), which tiles_test.sh and test_tiles.cpp hold equal to the whole run; a missing
# tile or a part of another run is refused at the join with its name; a resubmitted job keeps
# what is made; the parts do not depend on the thread count. The jobs give the same whether
# they read and repair the mesh each (the first run below) or read the repaired mesh that a
# first job wrote (--pass mesh, as the cluster examples run it).
set -u
geotex=$1
examples=$(cd "$(dirname "$0")/../examples/cluster" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
passes="depth texels rims depth-without-rims texels-without-rims features"
# Half the shapes engraved: both orientations and a second smoothing, so every pass has work.
opts=(--scale 0.04 --orientation both --tiles 4)

"$geotex" synth -o m.ply --level 6 --engraved 0.5 --quiet >/dev/null || fail "synth"
"$geotex" synth -o n.ply --level 6 --engraved 0.5 --layout-seed 2 --quiet >/dev/null || fail "synth n"
cp m.ply m.ply.orig
"$geotex" segment m.ply "${opts[@]}" -o one.ply --json one.json --quiet >/dev/null || fail "segment --tiles 4"
"$geotex" segment m.ply --scale 0.04 --orientation both -o whole.ply --quiet >/dev/null || fail "segment whole"
cmp -s one.ply whole.ply || fail "--tiles 4 in one process is not the whole run's segmentation"

# Three shards over four tiles, each pass after the one before.
for pass in $passes; do
  parallel --will-cite --halt now,fail=1 "$geotex" segment m.ply "${opts[@]}" --tile-dir parts \
    --pass "$pass" --shard {}/3 --quiet ::: 1 2 3 >"$pass.out" 2>&1 || fail "pass $pass: $(cat "$pass.out")"
done
for pass in $passes; do
  n=$(ls parts/"$pass"/tile-*.part 2>/dev/null | wc -l)
  [ "$n" -eq 4 ] || fail "pass $pass: $n parts, not 4"
done
"$geotex" segment m.ply "${opts[@]}" --tile-dir parts -o joined.ply --json joined.json --quiet >/dev/null || fail "join"
cmp -s joined.ply one.ply || fail "the joined segmentation is not the one-process tiled run's"
cmp -s joined.json one.json || fail "the joined JSON report is not the one-process tiled run's"

# A job of several tiles says after each tile but its last about how long the rest will take.
"$geotex" segment m.ply "${opts[@]}" --tile-dir eta --pass depth >eta.out 2>&1 || fail "depth pass in one job: $(cat eta.out)"
[ "$(grep -c '(. of 4 here): [0-9.]* s, about [0-9.]* \(s\|min\|h\) left for [0-9] more$' eta.out)" -eq 3 ] ||
  fail "the depth job did not say the time left after each of its first 3 tiles: $(cat eta.out)"
grep -q "(4 of 4 here): [0-9.]* s$" eta.out || fail "the depth job's last tile's line is not its time alone: $(cat eta.out)"

# The cluster examples: GNU parallel on this machine (':' as the only host), and Slurm through
# a stand-in sbatch that runs each array's tasks at once, after checking that the job it
# depends on succeeded.
echo ":" >hosts
GEOTEX="$geotex" JSON=par.json "$examples/tiles-parallel.sh" hosts m.ply "par dir" "par out.ply" "${opts[@]}" \
  >par.log 2>&1 || fail "tiles-parallel.sh: $(tail -5 par.log)"
cmp -s "par out.ply" one.ply || fail "tiles-parallel.sh: not the one-process tiled run's segmentation"
cmp -s par.json one.json || fail "tiles-parallel.sh: not the one-process tiled run's report"
# The texels joined once: the first job after a texel pass that reads its tiles (the mesh pass
# has cut them) leaves them beside its parts, and the jobs after it, and the join, read them
# instead of every part.
for pass in texels texels-without-rims; do
  [ -s "par dir/$pass/joined-texels" ] || fail "no job left the joined texels of pass $pass"
done
"$geotex" segment m.ply "${opts[@]}" --tile-dir "par dir" --pass rims --tile 1 >again.out 2>&1 || fail "rims job again: $(cat again.out)"
grep -q "reading the joined texels" again.out || fail "rims job again joined the texels: $(cat again.out)"
"$geotex" segment m.ply "${opts[@]}" --tile-dir "par dir" -o joined2.ply >join2.out 2>&1 || fail "join again: $(cat join2.out)"
grep -q "reading the joined texels of pass texels " join2.out && grep -q "reading the joined texels of pass texels-without-rims" join2.out || fail "the join did not read the joined texels: $(cat join2.out)"
grep -q "reading the summaries of pass depth " join2.out && grep -q "reading the summaries of pass depth-without-rims" join2.out || fail "the join did not read the depth parts' summaries: $(cat join2.out)"
grep -q "joining pass depth" join2.out && fail "the join read the depth parts: $(cat join2.out)"
# Likewise the mesh's extent, which the mesh pass measured and left in DIR/mesh.extent.
[ -s "par dir/mesh.extent" ] || fail "the mesh pass left no mesh.extent"
grep -q "measuring the repaired mesh" join2.out && fail "the join measured the mesh again: $(cat join2.out)"
# Without them, the join merges the parts and measures the mesh, to the same outputs.
mv "par dir/texels/joined-texels" joined-texels.keep
mv "par dir/texels-without-rims/joined-texels" joined-second.keep
mv "par dir/mesh.extent" extent.keep
"$geotex" segment m.ply "${opts[@]}" --tile-dir "par dir" -o fromparts.ply --json fromparts.json >fromparts.out 2>&1 || fail "join from the parts: $(cat fromparts.out)"
grep -q "joining pass texels " fromparts.out && grep -q "measuring the repaired mesh" fromparts.out || fail "join from the parts: $(cat fromparts.out)"
cmp -s fromparts.ply one.ply && cmp -s fromparts.json one.json || fail "the join from the parts is not the one-process tiled run's"
# A damaged extent, or another mesh's: refused by name, with no output.
head -c 30 extent.keep >"par dir/mesh.extent"
"$geotex" segment m.ply "${opts[@]}" --tile-dir "par dir" -o damaged.ply >/dev/null 2>err.txt
rc=$?
[ "$rc" -eq 2 ] && grep -q "par dir/mesh.extent: damaged" err.txt || fail "damaged mesh.extent: exit $rc: $(cat err.txt)"
[ -e damaged.ply ] && fail "damaged mesh.extent: an output was written"
mv extent.keep "par dir/mesh.extent"
# A damaged one: refused by name by the jobs after and by the join, with no output.
head -c 100 joined-texels.keep >"par dir/texels/joined-texels"
"$geotex" segment m.ply "${opts[@]}" --tile-dir "par dir" --pass features --tile 2 >/dev/null 2>err.txt
rc=$?
[ "$rc" -eq 2 ] && grep -q "par dir/texels/joined-texels: damaged" err.txt || fail "damaged joined texels, features job: exit $rc: $(cat err.txt)"
"$geotex" segment m.ply "${opts[@]}" --tile-dir "par dir" -o damaged.ply >/dev/null 2>err.txt
rc=$?
[ "$rc" -eq 2 ] && grep -q "par dir/texels/joined-texels: damaged" err.txt || fail "damaged joined texels, join: exit $rc: $(cat err.txt)"
[ -e damaged.ply ] && fail "damaged joined texels: an output was written"
mv joined-texels.keep "par dir/texels/joined-texels"
mv joined-second.keep "par dir/texels-without-rims/joined-texels"
cat >sbatch <<'SBATCH'
#!/bin/bash
# Stand-in for Slurm's sbatch: --array=1-N runs the --wrap command N times with
# SLURM_ARRAY_TASK_ID; --dependency=afterok:ID refuses to run unless job ID succeeded.
tasks=""; wrap=""; after=""
for a in "$@"; do
  case $a in
    --array=1-*) tasks=${a#--array=1-} ;;
    --wrap=*) wrap=${a#--wrap=} ;;
    --dependency=afterok:*) after=${a#--dependency=afterok:} ;;
  esac
done
id=$(( $(cat sbatch.count 2>/dev/null || echo 0) + 1 ))
echo "$id" >sbatch.count
if [ -n "$after" ] && ! grep -qx "$after ok" sbatch.status; then echo "$id failed" >>sbatch.status; echo "$id"; exit 0; fi
status=ok
for i in $(seq 1 "${tasks:-1}"); do SLURM_ARRAY_TASK_ID=$i bash -c "$wrap" >>sbatch.log 2>&1 || status=failed; done
echo "$id $status" >>sbatch.status
echo "$id"
SBATCH
chmod +x sbatch
touch sbatch.status
GEOTEX="$geotex" SBATCH=$PWD/sbatch "$examples/tiles-slurm.sh" m.ply "slurm dir" "slurm out.ply" 3 "${opts[@]}" \
  >slurm.log 2>&1 || fail "tiles-slurm.sh: $(tail -5 slurm.log)"
[ "$(grep -c ' ok$' sbatch.status)" -eq 8 ] || fail "tiles-slurm.sh: not 8 jobs done: $(cat sbatch.status; tail -5 sbatch.log)"
cmp -s "slurm out.ply" one.ply || fail "tiles-slurm.sh: not the one-process tiled run's segmentation"

[ -s "slurm dir/mesh.part" ] && [ -s "par dir/mesh.part" ] || fail "the cluster examples made no mesh.part"

# A directory the join may only read (results shared read-only): the join cannot put the
# vertices in a scratch file there, so it holds them, says so, and gives the same outputs.
# Root writes past the mode bits: it makes the directory immutable instead, where it can.
chmod a-w "slurm dir"
touch "slurm dir/.w" 2>/dev/null && { rm -f "slurm dir/.w"; chattr +i "slurm dir" 2>/dev/null; }
if touch "slurm dir/.w" 2>/dev/null; then
  rm -f "slurm dir/.w"
  echo "note: no directory can be made read-only here: the join over one is not checked"
else
  "$geotex" segment m.ply "${opts[@]}" --tile-dir "slurm dir" -o ro.ply --json ro.json >ro.out 2>&1 || fail "join over a read-only directory: $(cat ro.out)"
  grep -q "slurm dir: cannot create a scratch file (.*); the vertices are held in memory" ro.out || fail "join over a read-only directory: no note: $(cat ro.out)"
  cmp -s ro.ply one.ply && cmp -s ro.json one.json || fail "join over a read-only directory: not the one-process tiled run's outputs"
fi
chattr -i "slurm dir" 2>/dev/null
chmod u+w "slurm dir"

# The mesh pass again: kept, not rewritten. Another mesh's or a damaged mesh.part: refused by
# name, by the jobs and by the join, with no output.
cp -p "par dir/mesh.part" mesh.before
"$geotex" segment m.ply "${opts[@]}" --tile-dir "par dir" --pass mesh >again.out 2>&1 || fail "mesh pass again: $(cat again.out)"
grep -q "pass mesh: made already" again.out || fail "mesh pass again: $(cat again.out)"
# Every tile mesh is there: nothing to cut, so no copy of the mesh to cut from.
grep -q "copying the mesh in the order of space" again.out && fail "mesh pass again: copied the mesh to cut tiles that are made: $(cat again.out)"
cmp -s mesh.before "par dir/mesh.part" || fail "mesh pass again: mesh.part rewritten"
"$geotex" segment n.ply "${opts[@]}" --tile-dir nmesh --pass mesh --quiet >/dev/null 2>&1 || fail "mesh pass of n.ply"
cp -p "par dir/mesh.extent" extent.keep
cp nmesh/mesh.extent "par dir/mesh.extent"
"$geotex" segment m.ply "${opts[@]}" --tile-dir "par dir" -o nextent.ply >/dev/null 2>err.txt
rc=$?
[ "$rc" -eq 2 ] && grep -q "par dir/mesh.extent: the mesh extent of another run" err.txt || fail "another mesh's mesh.extent: exit $rc: $(cat err.txt)"
[ -e nextent.ply ] && fail "another mesh's mesh.extent: an output was written"
mv extent.keep "par dir/mesh.extent"
# A bad mesh leaves nothing behind: the mesh pass reads its polygons into scratch files in DIR,
# which it makes for them and removes when the reading fails; a DIR that was there stays, with
# at most the record of the mesh's digest (written before the reading, and still true).
head -c 200000 m.ply >cut.ply
"$geotex" segment cut.ply "${opts[@]}" --tile-dir cutmesh --pass mesh >/dev/null 2>err.txt
rc=$?
[ "$rc" -eq 2 ] && grep -q "cut.ply" err.txt || fail "mesh pass of a truncated mesh: exit $rc: $(cat err.txt)"
[ -e cutmesh ] && fail "mesh pass of a truncated mesh: left the directory cutmesh"
"$geotex" segment cut.ply "${opts[@]}" --tile-dir cutparent/more/cutmesh --pass mesh >/dev/null 2>&1
[ -e cutparent ] && fail "mesh pass of a truncated mesh: left the directories cutparent/more/cutmesh"
mkdir cutmesh2
"$geotex" segment cut.ply "${opts[@]}" --tile-dir cutmesh2 --pass mesh >/dev/null 2>&1
[ -d cutmesh2 ] && [ "$(ls -A cutmesh2 | grep -v '^mesh.sha256$')" = "" ] || fail "mesh pass of a truncated mesh into an empty directory: $(ls -A cutmesh2)"
cp nmesh/mesh.part "par dir/mesh.part"
"$geotex" segment m.ply "${opts[@]}" --tile-dir "par dir" -o nmesh.ply >/dev/null 2>err.txt
rc=$?
[ "$rc" -eq 2 ] && grep -q "par dir/mesh.part: the prepared mesh of another run" err.txt || fail "another mesh's mesh.part at the join: exit $rc: $(cat err.txt)"
[ -e nmesh.ply ] && fail "another mesh's mesh.part: an output was written"
"$geotex" segment m.ply "${opts[@]}" --tile-dir "par dir" --pass mesh >/dev/null 2>err.txt
[ $? -eq 2 ] && grep -q "the prepared mesh of another run" err.txt || fail "mesh pass over another mesh's mesh.part: $(cat err.txt)"
head -c 1000 mesh.before >"par dir/mesh.part"
"$geotex" segment m.ply "${opts[@]}" --tile-dir "par dir" -o trunc.ply >/dev/null 2>err.txt
rc=$?
[ "$rc" -eq 2 ] && grep -q "par dir/mesh.part: damaged: the file ends inside its arrays" err.txt || fail "a truncated mesh.part: exit $rc: $(cat err.txt)"
[ -e trunc.ply ] && fail "a truncated mesh.part: an output was written"
# The join reads the faces from mesh.part as it needs them: a damaged index in the last face
# is refused all the same, by name, before anything is written.
cp mesh.before "par dir/mesh.part"
printf '\x7f' | dd of="par dir/mesh.part" bs=1 seek=$(($(stat -c %s mesh.before) - 1)) conv=notrunc status=none
"$geotex" segment m.ply "${opts[@]}" --tile-dir "par dir" -o badface.ply >/dev/null 2>err.txt
rc=$?
[ "$rc" -eq 2 ] && grep -q "par dir/mesh.part: damaged: face [0-9]* names a vertex past the last" err.txt || fail "a damaged face in mesh.part: exit $rc: $(cat err.txt)"
[ -e badface.ply ] && fail "a damaged face in mesh.part: an output was written"
# The mesh pass cuts its tiles from mesh.part's faces, a block at a time: a mesh.part made
# already is checked face by face all the same.
"$geotex" segment m.ply "${opts[@]}" --tile-dir "par dir" --pass mesh >/dev/null 2>err.txt
rc=$?
[ "$rc" -eq 2 ] && grep -q "par dir/mesh.part: damaged: face [0-9]* names a vertex past the last" err.txt || fail "mesh pass over a damaged face in mesh.part: exit $rc: $(cat err.txt)"
cp -p mesh.before "par dir/mesh.part"

# The mesh pass also cuts the tiles of the first depth pass (DIR/mesh/tile-K.part), whose jobs
# read their tile alone: their parts are the parts of the jobs that read the whole mesh.
n=$(ls "par dir"/mesh/tile-*.part 2>/dev/null | wc -l)
[ "$n" -eq 4 ] || fail "the mesh pass made $n tile meshes, not 4"
for k in 1 2 3 4; do
  cmp -s "par dir/depth/tile-$k.part" parts/depth/tile-$k.part || fail "tile $k's depth part from its tile mesh differs"
done
# Without mesh.part: the job never reads the whole mesh.
mkdir alone && cp -rp "par dir/mesh" alone/
"$geotex" segment m.ply "${opts[@]}" --tile-dir alone --pass depth --tile 2 >alone.out 2>&1 || fail "depth job from its tile alone: $(cat alone.out)"
grep -q "reading the mesh of tile 2" alone.out || fail "depth job from its tile alone: $(cat alone.out)"
grep -qE "^geotex: (reading|repair|reading the repaired mesh) +[0-9.]+ s" alone.out && fail "depth job from its tile alone read the mesh: $(cat alone.out)"
cmp -s alone/depth/tile-2.part parts/depth/tile-2.part || fail "tile 2's depth part from its tile alone differs"
# A damaged tile mesh, or another tile's: refused by the depth job with its name.
cp -p alone/mesh/tile-1.part tile1.before
head -c 3000 tile1.before >alone/mesh/tile-1.part
"$geotex" segment m.ply "${opts[@]}" --tile-dir alone --pass depth --tile 1 >/dev/null 2>err.txt
rc=$?
[ "$rc" -eq 2 ] && grep -q "alone/mesh/tile-1.part: damaged: the file ends inside its arrays" err.txt || fail "a truncated tile mesh: exit $rc: $(cat err.txt)"
cp alone/mesh/tile-3.part alone/mesh/tile-1.part
"$geotex" segment m.ply "${opts[@]}" --tile-dir alone --pass depth --tile 1 >/dev/null 2>err.txt
rc=$?
[ "$rc" -eq 2 ] && grep -q "alone/mesh/tile-1.part: the mesh of tile 3, not of tile 1" err.txt || fail "another tile's mesh: exit $rc: $(cat err.txt)"
[ -e alone/depth/tile-1.part ] && fail "a refused tile mesh: a part was written"
# The mesh pass checks the tile meshes there, refusing a damaged one, and makes those missing.
"$geotex" segment m.ply "${opts[@]}" --tile-dir alone --pass mesh >/dev/null 2>err.txt
[ $? -eq 2 ] && grep -q "alone/mesh/tile-1.part: the mesh of tile 3" err.txt || fail "mesh pass over another tile's mesh: $(cat err.txt)"
rm alone/mesh/tile-1.part
cp -p "par dir/mesh.part" alone/
"$geotex" segment m.ply "${opts[@]}" --tile-dir alone --pass mesh >again.out 2>&1 || fail "mesh pass remaking a tile mesh: $(cat again.out)"
grep -q "pass mesh: 1 tile mesh made, 4 in all" again.out || fail "mesh pass remaking a tile mesh: $(cat again.out)"
grep -q "copying the mesh in the order of space" again.out || fail "mesh pass remaking a tile mesh: no copy to cut it from: $(cat again.out)"
cmp -s tile1.before alone/mesh/tile-1.part || fail "the tile mesh made again differs"

# The first texel pass too: from the tile meshes and the depth parts, the same parts.
for k in 1 2 3 4; do
  cmp -s "par dir/texels/tile-$k.part" parts/texels/tile-$k.part || fail "tile $k's texel part from its tile mesh differs"
done
mkdir texalone && cp -rp "par dir/mesh" "par dir/depth" texalone/
"$geotex" segment m.ply "${opts[@]}" --tile-dir texalone --pass texels --tile 3 >texalone.out 2>&1 || fail "texel job from its tile alone: $(cat texalone.out)"
grep -q "the seeds' thresholds" texalone.out || fail "texel job from its tile alone: $(cat texalone.out)"
grep -qE "^geotex: (reading|repair|reading the repaired mesh) +[0-9.]+ s" texalone.out && fail "texel job from its tile alone read the mesh: $(cat texalone.out)"
cmp -s texalone/texels/tile-3.part parts/texels/tile-3.part || fail "tile 3's texel part from its tile alone differs"
# The first texel job left the thresholds; the next reads them instead of merging again.
[ -s texalone/texels/seed-thresholds ] || fail "the first texel job left no seed-thresholds"
"$geotex" segment m.ply "${opts[@]}" --tile-dir texalone --pass texels --tile 2 >texalone.out 2>&1 || fail "second texel job: $(cat texalone.out)"
grep -q "reading the seeds' thresholds" texalone.out || fail "second texel job merged the depths again: $(cat texalone.out)"
cmp -s texalone/texels/tile-2.part parts/texels/tile-2.part || fail "tile 2's texel part from the thresholds left differs"
cp -p texalone/texels/seed-thresholds thresholds.keep
printf 'x' >texalone/texels/seed-thresholds
rm texalone/texels/tile-2.part
"$geotex" segment m.ply "${opts[@]}" --tile-dir texalone --pass texels --tile 2 >/dev/null 2>err.txt
rc=$?
[ "$rc" -eq 2 ] && grep -q "texalone/texels/seed-thresholds: not a geotex seed thresholds file" err.txt || fail "damaged seed-thresholds: exit $rc: $(cat err.txt)"
[ -e texalone/texels/tile-2.part ] && fail "damaged seed-thresholds: a part was written"
cp -p thresholds.keep texalone/texels/seed-thresholds
# The job that ends the pass joins its texels for the jobs after it; the jobs before it, with
# parts missing, do not.
[ -e texalone/texels/joined-texels ] && fail "a texel job joined the texels with parts missing"
"$geotex" segment m.ply "${opts[@]}" --tile-dir texalone --pass texels >texalone.out 2>&1 || fail "the texel pass's last job: $(cat texalone.out)"
grep -q "joining the texels" texalone.out || fail "the texel pass's last job did not join the texels: $(cat texalone.out)"
cmp -s texalone/texels/joined-texels "par dir/texels/joined-texels" || fail "the joined texels differ from the parallel run's"
rm texalone/depth/tile-4.part
"$geotex" segment m.ply "${opts[@]}" --tile-dir texalone --pass texels --tile 1 >/dev/null 2>err.txt
rc=$?
[ "$rc" -eq 2 ] && grep -q "texalone/depth: tile 4 of 4 has no part" err.txt || fail "texel job without a depth part: exit $rc: $(cat err.txt)"
# A rims job with the tile meshes and the texel parts alone: the texels joined from the parts
# and the same part, with neither the mesh nor a depth part read.
mkdir rimalone && cp -rp "par dir/mesh" "par dir/texels" rimalone/ && rm rimalone/texels/joined-texels
"$geotex" segment m.ply "${opts[@]}" --tile-dir rimalone --pass rims --tile 2 >rimalone.out 2>&1 || fail "rims job from its tile alone: $(cat rimalone.out)"
grep -q "joining the texels" rimalone.out || fail "rims job from its tile alone: $(cat rimalone.out)"
grep -qE "^geotex: (reading|repair|reading the repaired mesh) +[0-9.]+ s" rimalone.out && fail "rims job from its tile alone read the mesh: $(cat rimalone.out)"
cmp -s rimalone/rims/tile-2.part parts/rims/tile-2.part || fail "tile 2's rims part from its tile alone differs"
# The second smoothing likewise, from the rims parts and then its depth parts.
cp -p "par dir"/rims/*.part rimalone/rims/
"$geotex" segment m.ply "${opts[@]}" --tile-dir rimalone --pass depth-without-rims --tile 3 >rimalone.out 2>&1 || fail "second smoothing's depth job from its tile alone: $(cat rimalone.out)"
grep -q "joining the rims" rimalone.out || fail "second smoothing's depth job from its tile alone: $(cat rimalone.out)"
grep -qE "^geotex: (reading|repair|reading the repaired mesh) +[0-9.]+ s" rimalone.out && fail "second smoothing's depth job read the mesh: $(cat rimalone.out)"
cmp -s rimalone/depth-without-rims/tile-3.part parts/depth-without-rims/tile-3.part || fail "tile 3's second depth part from its tile alone differs"
# The other tiles' parts alone, as a directory made before the sorted depths has them: the
# texel job refuses, naming the tiles, and the depth pass run again makes them from the parts.
cp -p "par dir"/depth-without-rims/*.part rimalone/depth-without-rims/
"$geotex" segment m.ply "${opts[@]}" --tile-dir rimalone --pass texels-without-rims --tile 4 >/dev/null 2>err.txt
rc=$?
[ "$rc" -eq 2 ] && grep -q "rimalone/depth-without-rims: tiles 1, 2, 4 of 4 have no sorted depths" err.txt || fail "texel job without sorted depths: exit $rc: $(cat err.txt)"
"$geotex" segment m.ply "${opts[@]}" --tile-dir rimalone --pass depth-without-rims >rimalone.out 2>&1 || fail "depth job making sorted depths from its parts: $(cat rimalone.out)"
[ "$(grep -c "its sorted depths made from it" rimalone.out)" -eq 3 ] || fail "depth job making sorted depths from its parts: $(cat rimalone.out)"
for k in 1 2 3 4; do
  cmp -s rimalone/depth-without-rims/tile-$k.sorted "par dir"/depth-without-rims/tile-$k.sorted || fail "tile $k's sorted depths made from its part differ"
done
"$geotex" segment m.ply "${opts[@]}" --tile-dir rimalone --pass texels-without-rims --tile 4 >rimalone.out 2>&1 || fail "second texel job from its tile alone: $(cat rimalone.out)"
grep -q "the seeds' thresholds" rimalone.out || fail "second texel job from its tile alone: $(cat rimalone.out)"
grep -qE "^geotex: (reading|repair|reading the repaired mesh) +[0-9.]+ s" rimalone.out && fail "second texel job read the mesh: $(cat rimalone.out)"
cmp -s rimalone/texels-without-rims/tile-4.part parts/texels-without-rims/tile-4.part || fail "tile 4's second texel part from its tile alone differs"
# And the features, from both texel passes and both depth passes.
cp -p "par dir"/texels-without-rims/*.part rimalone/texels-without-rims/
cp -rp "par dir/depth" rimalone/
"$geotex" segment m.ply "${opts[@]}" --tile-dir rimalone --pass features >rimalone.out 2>&1 || fail "features jobs from their tiles alone: $(cat rimalone.out)"
grep -q "joining the texels without rims" rimalone.out || fail "features jobs from their tiles alone: $(cat rimalone.out)"
grep -q "reading the joined texels" rimalone.out || fail "features jobs joined the texels the rims job left: $(cat rimalone.out)"
grep -qE "^geotex: (reading|repair|reading the repaired mesh) +[0-9.]+ s" rimalone.out && fail "features jobs read the mesh: $(cat rimalone.out)"
for k in 1 2 3 4; do
  cmp -s rimalone/features/tile-$k.part parts/features/tile-$k.part || fail "tile $k's features part from its tile alone differs"
done
rm rimalone/texels/tile-3.part
"$geotex" segment m.ply "${opts[@]}" --tile-dir rimalone --pass rims --tile 1 >/dev/null 2>err.txt
rc=$?
[ "$rc" -eq 2 ] && grep -q "rimalone/texels: tile 3 of 4 has no part" err.txt || fail "rims job without a texel part: exit $rc: $(cat err.txt)"
# With --keep-rims the pass has nothing to do, and says so.
for pass in mesh depth texels; do
  "$geotex" segment m.ply "${opts[@]}" --keep-rims --tile-dir kept --pass $pass --quiet >/dev/null 2>&1 || fail "--keep-rims: pass $pass"
done
"$geotex" segment m.ply "${opts[@]}" --keep-rims --tile-dir kept --pass rims >kept.out 2>&1 || fail "--keep-rims: pass rims: $(cat kept.out)"
grep -q "pass rims is not needed in this run (--keep-rims)" kept.out || fail "--keep-rims: pass rims: $(cat kept.out)"
[ -e kept/rims ] && fail "--keep-rims: pass rims made parts"
# Sphere-1's details are all raised: the rims pass has work (its negative texels are noise
# by the positive shapes), but no detail is left out of a second smoothing. Its jobs learn
# that from the rims parts alone, without joining the texels, and the join is the one-process
# tiled run's.
"$geotex" synth -o s.ply --level 6 --quiet >/dev/null || fail "synth s"
sopts=(--scale 0.04 --tiles 4)
for pass in mesh depth texels rims depth-without-rims texels-without-rims features; do
  "$geotex" segment s.ply "${sopts[@]}" --tile-dir raised --pass $pass >$pass.raised 2>&1 || fail "sphere-1, pass $pass: $(cat $pass.raised)"
done
[ "$(ls raised/rims | wc -l)" -eq 4 ] || fail "sphere-1: the rims pass made no parts, so the check below tests nothing"
for pass in depth-without-rims texels-without-rims; do
  grep -q "pass $pass is not needed in this run (no detail is left out of a second smoothing)" $pass.raised || fail "sphere-1, pass $pass: $(cat $pass.raised)"
  grep -q "joining the texels" $pass.raised && fail "sphere-1, pass $pass: joined the texels to find it has nothing to do"
done
"$geotex" segment s.ply "${sopts[@]}" --tile-dir raised -o raised.ply --quiet >/dev/null || fail "sphere-1: join"
"$geotex" segment s.ply "${sopts[@]}" -o raised-one.ply --quiet >/dev/null || fail "sphere-1: one process"
cmp -s raised.ply raised-one.ply || fail "sphere-1: the joined segmentation is not the one-process tiled run's"

# A ridge 50r long across a square grid: its texel outgrows every tile's halo, and the job
# reads the whole mesh for the tiles it crosses, with the same parts.
awk 'BEGIN { n = 120; print "OFF"; print (n + 1) * (n + 1), 2 * n * n, 0;
  for (j = 0; j <= n; j++) for (i = 0; i <= n; i++) { x = i / n - 0.5; y = j / n - 0.5;
    printf "%.9f %.9f %.9f\n", x, y, 0.01 * exp(-(x - 0.3) ^ 2 / (2 * 0.012 ^ 2)) }
  for (j = 0; j < n; j++) for (i = 0; i < n; i++) { a = j * (n + 1) + i; b = a + 1; c = a + n + 1;
    print 3, a, b, c + 1; print 3, a, c + 1, c } }' >ridge.off
ropts=(--scale 0.02 --tiles 4)
"$geotex" segment ridge.off "${ropts[@]}" --tile-dir ridge-whole --pass depth --quiet >/dev/null || fail "ridge: depth"
"$geotex" segment ridge.off "${ropts[@]}" --tile-dir ridge-whole --pass texels --quiet >/dev/null || fail "ridge: texels"
"$geotex" segment ridge.off "${ropts[@]}" --tile-dir ridge-cut --pass mesh --quiet >/dev/null || fail "ridge: mesh"
"$geotex" segment ridge.off "${ropts[@]}" --tile-dir ridge-cut --pass depth --quiet >/dev/null || fail "ridge: depth from tiles"
"$geotex" segment ridge.off "${ropts[@]}" --tile-dir ridge-cut --pass texels >ridge.out 2>&1 || fail "ridge: texels from tiles: $(cat ridge.out)"
grep -q "a texel grows past the tile's halo; the whole mesh is read for it" ridge.out || fail "ridge: no tile outgrown: $(cat ridge.out)"
same_ridge_parts() {  # pass: the parts read from the tiles are those read from the mesh
  for k in 1 2 3 4; do
    cmp -s ridge-whole/$1/tile-$k.part ridge-cut/$1/tile-$k.part || fail "ridge: tile $k's $1 part differs"
  done
}
same_ridge_parts texels
# So does the features job for the tile that owns the ridge's first face.
for pass in rims depth-without-rims texels-without-rims; do
  for dir in ridge-whole ridge-cut; do
    "$geotex" segment ridge.off "${ropts[@]}" --tile-dir $dir --pass $pass --quiet >/dev/null 2>&1 || fail "ridge: $pass in $dir"
  done
done
"$geotex" segment ridge.off "${ropts[@]}" --tile-dir ridge-whole --pass features --quiet >/dev/null || fail "ridge: features"
"$geotex" segment ridge.off "${ropts[@]}" --tile-dir ridge-cut --pass features >ridge.out 2>&1 || fail "ridge: features from tiles: $(cat ridge.out)"
grep -q "a texel and its curvature discs reach past the tile's halo; the whole mesh is read for it" ridge.out || fail "ridge: no features tile outgrown: $(cat ridge.out)"
same_ridge_parts features

# A resubmitted job keeps what is made: no part is rewritten.
cp -p parts/texels/tile-2.part before.part
"$geotex" segment m.ply "${opts[@]}" --tile-dir parts --pass texels --tile 2 >again.out 2>&1 || fail "resubmitted job: $(cat again.out)"
grep -q "made already" again.out || fail "resubmitted job: no 'made already' in: $(cat again.out)"
cmp -s before.part parts/texels/tile-2.part || fail "resubmitted job rewrote its part"

# One thread or two: the same parts.
"$geotex" segment m.ply "${opts[@]}" --tile-dir one-thread --pass depth --threads 1 --quiet >/dev/null || fail "pass depth, --threads 1"
for k in 1 2 3 4; do
  cmp -s parts/depth/tile-$k.part one-thread/depth/tile-$k.part || fail "tile $k's depth part differs with --threads 1"
done

# A missing tile: refused at the join with the pass, the tile and the command; no output.
mv parts/features/tile-3.part held.part
"$geotex" segment m.ply "${opts[@]}" --tile-dir parts -o missing.ply >/dev/null 2>err.txt
rc=$?
[ "$rc" -eq 2 ] || fail "missing tile: exit $rc, not 2"
grep -q "parts/features: tile 3 of 4 has no part" err.txt || fail "missing tile: $(cat err.txt)"
grep -q -- "--pass features" err.txt || fail "missing tile: the command that makes it is not named: $(cat err.txt)"
[ -e missing.ply ] && fail "missing tile: an output was written"
mv held.part parts/features/tile-3.part

# A tile's depth part and its sorted depths of another run (another --min-faces) among this
# run's: refused with their names. The join reads a depth pass's sorted depths' headers (the
# greatest depths and counts are all it takes of the parts), a job the parts.
"$geotex" segment m.ply "${opts[@]}" --min-faces 5 --tile-dir other --pass depth --tile 2 --quiet >/dev/null || fail "other run's pass"
cp parts/depth/tile-2.part held.part
cp parts/depth/tile-2.sorted held.sorted
cp other/depth/tile-2.part parts/depth/tile-2.part
cp other/depth/tile-2.sorted parts/depth/tile-2.sorted
"$geotex" segment m.ply "${opts[@]}" --tile-dir parts -o mixed.ply >/dev/null 2>err.txt
rc=$?
[ "$rc" -eq 2 ] || fail "mixed runs: exit $rc, not 2"
grep -q "parts/depth/tile-2.sorted: the sorted depths file of another run" err.txt || fail "mixed runs: $(cat err.txt)"
[ -e mixed.ply ] && fail "mixed runs: an output was written"
# ... and a job of this run does not build on the part either.
"$geotex" segment m.ply "${opts[@]}" --tile-dir parts --pass texels --tile 1 >/dev/null 2>err.txt
[ $? -eq 2 ] && grep -q "parts/depth/tile-2.part: a part of another run" err.txt || fail "a job over a mixed pass: $(cat err.txt)"
cp held.part parts/depth/tile-2.part
cp held.sorted parts/depth/tile-2.sorted
# Without the sorted depths (a directory made before them), the join reads the depth parts, to
# the same outputs.
mkdir sorted.keep && mv parts/depth/*.sorted sorted.keep/
"$geotex" segment m.ply "${opts[@]}" --tile-dir parts -o nosorted.ply --json nosorted.json >nosorted.out 2>&1 || fail "join without sorted depths: $(cat nosorted.out)"
grep -q "joining pass depth " nosorted.out && ! grep -q "reading the summaries of pass depth " nosorted.out || fail "join without sorted depths: $(cat nosorted.out)"
cmp -s nosorted.ply one.ply && cmp -s nosorted.json one.json || fail "the join without sorted depths is not the one-process tiled run's"
mv sorted.keep/*.sorted parts/depth/
# The jobs take the mesh's digest from the record beside the parts while the file's signature
# is unchanged: the record holds the file's own digest, and a mesh rewritten in place (same
# name, inode, size and modification time: only its change time tells) is read again.
[ "$(sed -n 3p parts/mesh.sha256)" = "$(sha256sum m.ply | cut -d' ' -f1)" ] || fail "the remembered digest is not the mesh's: $(cat parts/mesh.sha256)"
# A record whose digest is wrong is believed while the signature holds: proof that it is read.
cp parts/mesh.sha256 record.keep
sed -i '3s/.*/'"$(printf '0%.0s' $(seq 64))"'/' parts/mesh.sha256
"$geotex" segment m.ply "${opts[@]}" --tile-dir parts -o believed.ply >/dev/null 2>err.txt
[ $? -eq 2 ] && grep -q "of another run" err.txt || fail "a record with another digest was not read: $(cat err.txt)"
cp record.keep parts/mesh.sha256
[ "$(stat -c %s n.ply)" = "$(stat -c %s m.ply)" ] || fail "n.ply and m.ply differ in size: the check below would not test the signature"
cp -p m.ply m.keep
cat n.ply >m.ply && touch -r m.keep m.ply
"$geotex" segment m.ply "${opts[@]}" --tile-dir parts -o rewritten.ply >/dev/null 2>err.txt
[ $? -eq 2 ] && grep -q "of another run" err.txt || fail "a mesh rewritten in place: $(cat err.txt)"
cat m.keep >m.ply && touch -r m.keep m.ply
# The same with another mesh: its digest is part of the run's key.
"$geotex" segment n.ply "${opts[@]}" --tile-dir parts -o n.ply.out >/dev/null 2>err.txt
[ $? -eq 2 ] && grep -q "of another run" err.txt || fail "another mesh: $(cat err.txt)"

# A pass before the one before it: refused, naming what is missing.
"$geotex" segment m.ply "${opts[@]}" --tile-dir early --pass texels >/dev/null 2>err.txt
rc=$?
[ "$rc" -eq 2 ] && grep -q "early/depth: tiles 1, 2, 3, 4 of 4 have no part" err.txt || fail "texels before depth: exit $rc: $(cat err.txt)"
[ -e early/texels ] && fail "texels before depth: a part was written"

# A pass the run does not need: said, nothing written (--keep-rims: no rims, no second
# smoothing), and the join goes from the texels to the features.
for pass in $passes; do
  "$geotex" segment m.ply "${opts[@]}" --keep-rims --tile-dir kept --pass "$pass" >"$pass.kept" 2>&1 || fail "--keep-rims, pass $pass: $(cat "$pass.kept")"
done
for pass in rims depth-without-rims texels-without-rims; do
  grep -q "pass $pass is not needed in this run (--keep-rims)" $pass.kept || fail "--keep-rims, pass $pass: $(cat $pass.kept)"
  [ -e kept/$pass ] && fail "--keep-rims, pass $pass: a directory was written"
  grep -q "joining" $pass.kept && fail "--keep-rims, pass $pass: joined parts to find it has nothing to do: $(cat $pass.kept)"
done
"$geotex" segment m.ply "${opts[@]}" --keep-rims --tile-dir kept -o kept.ply --quiet >/dev/null || fail "--keep-rims: join"
"$geotex" segment m.ply --scale 0.04 --orientation both --keep-rims -o kept-whole.ply --quiet >/dev/null || fail "--keep-rims: whole"
cmp -s kept.ply kept-whole.ply || fail "--keep-rims: the joined segmentation is not the whole run's"

# Usage errors.
usage() {  # expected-text args...
  local want=$1; shift
  "$geotex" segment m.ply "$@" >/dev/null 2>err.txt
  local rc=$?
  [ "$rc" -eq 1 ] && grep -q -- "$want" err.txt || fail "segment $*: exit $rc: $(cat err.txt)"
}
usage "need --tile-dir" "${opts[@]}" --pass depth
usage "is not a pass" "${opts[@]}" --tile-dir parts --pass dept
usage "tiles are numbered 1 to 4" "${opts[@]}" --tile-dir parts --pass depth --tile 5
usage "not both" "${opts[@]}" --tile-dir parts --pass depth --tile 1 --shard 1/2
usage "is not i/N" "${opts[@]}" --tile-dir parts --pass depth --shard 1
usage "needs --tiles" --scale 0.04 --tile-dir parts
usage "choose the tiles of a --pass" "${opts[@]}" --tile-dir parts --tile 1 -o x.ply
usage "give --output and --json to the run without --pass" "${opts[@]}" --tile-dir parts --pass depth -o x.ply
usage "--output is required" "${opts[@]}" --tile-dir parts
usage "the directory name is empty" "${opts[@]}" --tile-dir "" -o x.ply
usage "'' is not a pass" "${opts[@]}" --tile-dir parts --pass ""
usage "--tile" "${opts[@]}" --tile-dir parts --pass depth --tile nan
usage "--tile" "${opts[@]}" --tile-dir parts --pass depth --tile ""
usage "--tile" "${opts[@]}" --tile-dir parts --pass depth --tile 0
usage "is not i/N" "${opts[@]}" --tile-dir parts --pass depth --shard ""
usage "no --tile or --shard" "${opts[@]}" --tile-dir parts --pass mesh --tile 1
usage "no --tile or --shard" "${opts[@]}" --tile-dir parts --pass mesh --shard 1/2
usage "is not a pass (mesh, depth," "${opts[@]}" --tile-dir parts --pass mesh2
[ -e x.ply ] && fail "a usage error wrote x.ply"
# A --tile-dir that is the mesh itself: no directory there, refused before any work.
"$geotex" segment m.ply "${opts[@]}" --tile-dir m.ply --pass depth >/dev/null 2>err.txt
rc=$?
[ "$rc" -eq 4 ] && grep -q "m.ply/depth" err.txt || fail "--tile-dir naming the mesh: exit $rc: $(cat err.txt)"
"$geotex" segment m.ply "${opts[@]}" --tile-dir m.ply --pass mesh >/dev/null 2>err.txt
rc=$?
[ "$rc" -eq 4 ] && grep -q "m.ply" err.txt || fail "--tile-dir naming the mesh, pass mesh: exit $rc: $(cat err.txt)"
cmp -s m.ply m.ply.orig || fail "--tile-dir naming the mesh: the mesh changed"

# A mesh without detail: Otsu finds no split, the threshold is infinite, and every job and the
# join give the one-process run's zero texels.
python3 - <<'PY'
n = 30
vertices = [(i / n, j / n, 0.0) for j in range(n + 1) for i in range(n + 1)]
faces = []
for j in range(n):
    for i in range(n):
        a = j * (n + 1) + i
        faces += [(a, a + 1, a + n + 2), (a, a + n + 2, a + n + 1)]
with open("flat.off", "w") as f:
    f.write("OFF\n%d %d 0\n" % (len(vertices), len(faces)))
    f.writelines("%g %g %g\n" % v for v in vertices)
    f.writelines("3 %d %d %d\n" % t for t in faces)
PY
flat=(--scale 0.05 --tiles 4)
"$geotex" segment flat.off "${flat[@]}" -o flat-one.ply --json flat-one.json --quiet >/dev/null 2>&1 || fail "flat mesh in one process"
for pass in mesh $passes; do
  "$geotex" segment flat.off "${flat[@]}" --tile-dir flat --pass "$pass" --quiet >flat.out 2>&1 || fail "flat mesh, pass $pass: $(cat flat.out)"
done
"$geotex" segment flat.off "${flat[@]}" --tile-dir flat -o flat-jobs.ply --json flat-jobs.json --quiet >flat.out 2>&1 || fail "flat mesh, join: $(cat flat.out)"
cmp -s flat-jobs.ply flat-one.ply || fail "flat mesh: the jobs' PLY is not the one-process run's"
grep -q '"texels": \[\]' flat-jobs.json || fail "flat mesh: the jobs found texels: $(head -c 300 flat-jobs.json)"

# Every vertex but three in one tile: a bumped sphere and, 40 radii away, one small triangle,
# so that the bounding box is 20 times the sphere's and in 9 tiles the sphere lies in tile 1,
# the triangle in tile 9 and seven tiles are empty. Every job and the join still give the
# one-process run.
"$geotex" synth --level 5 --ascii -o lone.ply --quiet >/dev/null || fail "synth for one tile"
python3 - <<'PY'
lines = open("lone.ply").read().splitlines()
end = lines.index("end_header")
nv = int(next(l for l in lines if l.startswith("element vertex")).split()[2])
nf = int(next(l for l in lines if l.startswith("element face")).split()[2])
vertices = lines[end + 1:end + 1 + nv]
faces = lines[end + 1 + nv:end + 1 + nv + nf]
with open("onetile.off", "w") as f:
    f.write("OFF\n%d %d 0\n" % (nv + 3, nf + 1))
    f.writelines(v + "\n" for v in vertices + ["40 40 40", "40.01 40 40", "40 40.01 40"])
    f.writelines(t + "\n" for t in faces)
    f.write("3 %d %d %d\n" % (nv, nv + 1, nv + 2))
PY
lone=(--radius 0.08 --tiles 9)
"$geotex" segment onetile.off "${lone[@]}" -o lone-one.ply --quiet >/dev/null 2>&1 || fail "one tile: one process"
for pass in mesh $passes; do
  "$geotex" segment onetile.off "${lone[@]}" --tile-dir lone --pass "$pass" --quiet >lone.out 2>&1 ||
    fail "one tile, pass $pass: $(cat lone.out)"
done
"$geotex" segment onetile.off "${lone[@]}" --tile-dir lone -o lone-jobs.ply --quiet >lone.out 2>&1 ||
  fail "one tile, join: $(cat lone.out)"
cmp -s lone-jobs.ply lone-one.ply || fail "one tile: the jobs' PLY is not the one-process run's"
empty=0
for k in 2 3 4 5 6 7 8; do
  [ "$(stat -c %s lone/mesh/tile-$k.part)" -lt 1000 ] && empty=$((empty + 1))
done
[ "$empty" = 7 ] && [ "$(stat -c %s lone/mesh/tile-1.part)" -gt 100000 ] ||
  fail "one tile: the sphere is not alone in tile 1: $(ls -l lone/mesh)"

[ "$failures" -eq 0 ] && echo "tile jobs tests passed" || { echo "$failures tile jobs test(s) failed"; exit 1; }
