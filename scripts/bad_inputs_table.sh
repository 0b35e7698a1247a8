#!/usr/bin/env bash
# Acceptance table: each bad input -> exit, message, wall time, peak RSS (/usr/bin/time -v).
FB=${FB:-${CARGO_TARGET_DIR:-target}/release/facebem}
CORPUS=$(cd "$(dirname "$0")/.." && pwd)/tests/bad_inputs
FACE=$(cd "$(dirname "$0")/.." && pwd)/assets/mediapipe_canonical_4loop.obj
W=$(mktemp -d)
row() { # name, command...
  local name=$1; shift
  /usr/bin/time -v -o $W/time.txt "$@" >$W/out.txt 2>$W/err.txt
  local code=$?
  local t=$(grep "Elapsed (wall" $W/time.txt | awk '{print $NF}')
  local m=$(grep "Maximum resident" $W/time.txt | awk '{print $NF}')
  local u=$(grep "User time" $W/time.txt | awk '{print $NF}')
  local k=$(grep "System time" $W/time.txt | awk '{print $NF}')
  local cpu=$(awk "BEGIN{print $u + $k}")
  local msg=$(head -1 $W/err.txt | cut -c1-150 | sed 's/|/\\|/g')
  echo "| $name | $code | $t | ${cpu} s | $((m/1024)) MB | $msg |"
}
echo "| input | exit | wall | CPU | peak RSS | message (first 150 chars) |"
echo "|---|---|---|---|---|---|"
grep -v '^#' $CORPUS/EXPECTED.tsv | while IFS=$'\t' read f code needle; do
  [ -z "$f" ] && continue
  d=$(mktemp -d); cp $CORPUS/$f $d/
  if [[ $f == *.muscles ]]; then
    row "$f" $FB rig $FACE --muscles $d/$f -o $d/out.rig
  else
    row "$f" $FB info $d/$f
  fi
  rm -rf $d
done
d=$(mktemp -d); $FB rig $FACE -o $d/a.rig >/dev/null 2>&1; cp $FACE $d/face.obj; ln $d/a.rig $d/hard.obj; mkfifo $d/fifo.obj; ln -s $d/a.rig $d/sym.obj
row "pose a.rig -o a.rig" $FB pose $d/a.rig -o $d/a.rig
row "pose a.rig -o hardlink-of-a.rig.obj" $FB pose $d/a.rig -o $d/hard.obj
row "export a.rig --gltf a.rig" $FB export $d/a.rig --gltf $d/a.rig
row "rig face.obj -o face.obj" $FB rig $d/face.obj -o $d/face.obj
row "pose face.obj -o face.obj" $FB pose $d/face.obj -o $d/face.obj
row "pose a.rig -o symlink.obj" $FB pose $d/a.rig -o $d/sym.obj
row "pose a.rig -o fifo.obj" $FB pose $d/a.rig -o $d/fifo.obj
row "export a.rig --gltf /dev/null" $FB export $d/a.rig --gltf /dev/null
row "info fifo.obj (FIFO input)" $FB info $d/fifo.obj
row "rig face.obj -o missing_dir/x.rig" $FB rig $d/face.obj -o $d/missing_dir/x.rig
row "export face.obj --gltf out.obj" $FB export $d/face.obj --gltf $d/out.obj
row "pose face.obj -o p.glb" $FB pose $d/face.obj -o $d/p.glb
row "pose face.obj --set buccinator=1 -o p.obj" $FB pose $d/face.obj --set buccinator=1 -o $d/p.obj
row "rig face.obj --poisson -1 -o x.rig" $FB rig $d/face.obj --poisson -1 -o $d/x.rig
echo; echo "files left in the output folder: $(ls -A $d | tr '\n' ' ')"
cmp <(cat $FACE) $d/face.obj && echo "face.obj unchanged"
