#!/usr/bin/env bash
# Kill -9 the moment our temporary file appears (i.e. during the write), N times per command.
FB=${FB:-${CARGO_TARGET_DIR:-target}/release/facebem}
FACE=$(cd "$(dirname "$0")/.." && pwd)/assets/mediapipe_canonical_4loop.obj
N=${N:-20}
d=$(mktemp -d); $FB rig $FACE -o $d/ref.rig >/dev/null 2>&1
$FB pose $d/ref.rig --preset happy -o $d/ref.obj >/dev/null; $FB export $d/ref.rig --gltf $d/ref.glb >/dev/null; $FB muscles $d/ref.rig -o $d/ref.muscles >/dev/null
declare -A cmd
cmd[rig]="$FB rig $FACE -o OUT.rig"
cmd[pose]="$FB pose $d/ref.rig --preset happy -o OUT.obj"
cmd[export]="$FB export $d/ref.rig --gltf OUT.glb"
cmd[muscles]="$FB muscles $d/ref.rig -o OUT.muscles"
for k in rig pose export muscles; do
  ext=${cmd[$k]##*.}; absent=0; complete=0; partial=0; tmpseen=0; tmpleft=0
  for i in $(seq $N); do
    w=$(mktemp -d); c=${cmd[$k]//OUT/$w/out}
    $c >/dev/null 2>&1 & pid=$!
    while kill -0 $pid 2>/dev/null; do
      if compgen -G "$w/.facebem-*" >/dev/null; then kill -9 $pid; break; fi
    done
    wait $pid 2>/dev/null
    if [ ! -e $w/out.$ext ]; then absent=$((absent+1));
    else
      case $k in
        rig) $FB info $w/out.rig >/dev/null 2>&1 && complete=$((complete+1)) || partial=$((partial+1));;
        *) cmp -s $w/out.$ext $d/ref.$ext && complete=$((complete+1)) || partial=$((partial+1));;
      esac
    fi
    compgen -G "$w/.facebem-*" >/dev/null && tmpseen=$((tmpseen+1))
    $FB pose $d/ref.rig -o $w/next.obj >/dev/null 2>&1
    compgen -G "$w/.facebem-*" >/dev/null && tmpleft=$((tmpleft+1))
    rm -rf $w
  done
  echo "| $k | $N | $absent | $complete | $partial | $tmpseen | $tmpleft |"
done
