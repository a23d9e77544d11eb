#!/usr/bin/env bash
# draw-map.sh -- reproduce eureka-demo.wad by driving the Eureka map editor
# under a virtual X display (Xvfb) with xdotool.
#
# Everything in the output WAD is written by Eureka itself: this script only
# moves the mouse, presses keys and types into Eureka's own dialogs/panels.
#
# Usage:  ./draw-map.sh [OUTPUT.wad]        (default: next to this script)
# Env:    SHOTS=/some/dir   save a screenshot after each stage (debugging)
#         KEEP_TMP=1        keep the temporary work directory
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
OUT="${1:-$HERE/eureka-demo.wad}"
IWAD="${IWAD:-/usr/share/games/doom/freedoom2.wad}"
SHOTS="${SHOTS:-}"

die() { echo "draw-map.sh: ERROR: $*" >&2; [ -n "${TMP:-}" ] && [ -z "${KEEP_TMP:-}" ] && echo "  (temp dir with eureka.log is removed on exit; re-run with KEEP_TMP=1 SHOTS=/tmp/shots to debug)" >&2; exit 1; }

# ---------------------------------------------------------------- checks
for prog in eureka Xvfb xdotool xdpyinfo; do
    command -v "$prog" >/dev/null 2>&1 || die "'$prog' not found in PATH (need packages: eureka xvfb xdotool x11-utils)"
done
[ -r "$IWAD" ] || die "IWAD not readable: $IWAD (need package freedoom)"
if [ -n "$SHOTS" ]; then
    command -v import >/dev/null 2>&1 || die "SHOTS set but imagemagick 'import' not found"
    mkdir -p "$SHOTS"
fi

START_TS=$(date +%s)
TMP="$(mktemp -d /tmp/eureka-draw.XXXXXX)"
XVFB_PID=""
EU_PID=""
cleanup() {
    [ -n "$EU_PID" ] && kill "$EU_PID" 2>/dev/null || true
    [ -n "$XVFB_PID" ] && kill "$XVFB_PID" 2>/dev/null || true
    wait 2>/dev/null || true
    if [ -z "${KEEP_TMP:-}" ]; then rm -rf "$TMP"; else echo "temp dir kept: $TMP"; fi
}
trap cleanup EXIT

# ---------------------------------------------------------------- Xvfb on a free display
DISP=""
for n in $(seq 99 160); do
    if [ ! -e "/tmp/.X$n-lock" ] && [ ! -e "/tmp/.X11-unix/X$n" ]; then DISP=":$n"; break; fi
done
[ -n "$DISP" ] || die "no free X display number found"
Xvfb "$DISP" -screen 0 1280x1024x24 -nolisten tcp >"$TMP/xvfb.log" 2>&1 &
XVFB_PID=$!
export DISPLAY="$DISP"
for _ in $(seq 1 50); do xdpyinfo >/dev/null 2>&1 && break; sleep 0.1; done
xdpyinfo >/dev/null 2>&1 || die "Xvfb did not start on $DISP (see $TMP/xvfb.log)"

# ---------------------------------------------------------------- helpers
shot() { [ -n "$SHOTS" ] && import -window root "$SHOTS/$1.png" || true; }

# wait until a visible window whose name matches regex $1 exists; print its id
wait_win() {
    local id=""
    for _ in $(seq 1 150); do
        id=$(xdotool search --onlyvisible --name "$1" 2>/dev/null | head -1 || true)
        [ -n "$id" ] && { echo "$id"; return 0; }
        kill -0 "$EU_PID" 2>/dev/null || die "eureka exited unexpectedly (log: $TMP/eureka.log)"
        sleep 0.1
    done
    die "timed out waiting for window '$1'"
}

# Map coordinates -> screen pixel.  Calibrated for: main window resized to
# 1270x1000 at (1,20), 50% zoom, fresh map template centred (see README).
OX=494; OY=514
px() { echo $((OX + $1 / 2)) $((OY - $2 / 2)); }
at() { xdotool mousemove $(px "$1" "$2"); sleep 0.25; }
key() { xdotool key "$@"; sleep 0.25; }

# vertex mode: Space at each point (snap-to-grid is on); closing the loop
# on an existing vertex/line makes Eureka create the sector.
draw() {
    local p
    for p in "$@"; do at $p; key space; done
}

# type a value into a panel input field at screen position ($1,$2), Enter
panel_set() {
    xdotool mousemove "$1" "$2" click 1; sleep 0.2
    key End; key shift+Home
    xdotool type --delay 30 "$3"; sleep 0.1
    key Return
}

# ---------------------------------------------------------------- start Eureka
HOMEDIR="$TMP/home"; EUHOME="$TMP/eureka-home"
mkdir -p "$HOMEDIR" "$EUHOME"
# Eureka config: no GL nodes (their GL_MAPxx lump carries a TIME= stamp,
# which would make the output differ on every run); everything else default.
cat >"$EUHOME/config.cfg" <<'EOF'
bsp_on_save 1
bsp_gl_nodes 0
auto_load_recent 0
EOF
# HOME/XDG only matter for the GTK file chooser (recently-used.xbel etc.)
HOME="$HOMEDIR" XDG_CONFIG_HOME="$HOMEDIR/.config" XDG_DATA_HOME="$HOMEDIR/.local/share" \
XDG_CACHE_HOME="$HOMEDIR/.cache" NO_AT_BRIDGE=1 \
    eureka --home "$EUHOME" --iwad "$IWAD" --warp MAP01 --log "$TMP/eureka.log" \
    >"$TMP/eureka.out" 2>&1 &
EU_PID=$!

MAIN=$(wait_win 'freedoom2\.wad \(MAP01\)')
sleep 1
shot 01-start

# ---------------------------------------------------------------- File > New Project (Ctrl+N)
NEWWAD="$TMP/eureka-demo.wad"
xdotool windowfocus --sync "$MAIN"; sleep 0.3
xdotool mousemove 300 300; key ctrl+n
CHOOSER=$(wait_win '^Pick file to create$')
sleep 0.5
xdotool windowfocus --sync "$CHOOSER" 2>/dev/null || true; sleep 0.2
xdotool type --delay 20 "$NEWWAD"; sleep 0.3
key Return
PROJ=$(wait_win '^New Project$')
sleep 0.5
shot 02-newproject
# game freedoom2 / port vanilla / Doom format are the defaults: click "OK"
eval "$(xdotool getwindowgeometry --shell "$PROJ")"
xdotool mousemove $((X + 280)) $((Y + HEIGHT - 34)) click 1
MAIN=$(wait_win 'eureka-demo\.wad \(MAP01\)')
sleep 1
[ -f "$NEWWAD" ] || die "Eureka did not create $NEWWAD"

# bigger window, give it X keyboard focus (Eureka ignores mouse motion
# while it thinks it is unfocused, and there is no window manager here)
xdotool windowsize "$MAIN" 1270 1000; sleep 0.5
xdotool windowfocus --sync "$MAIN"; sleep 0.3
xdotool mousemove 490 520; sleep 0.3
shot 03-fresh

# ---------------------------------------------------------------- clear the template room
key v; key ctrl+a; key Delete          # vertices (+ their lines and sectors)
key t; key ctrl+a; key Delete          # the 4 player starts
# grid on, snap on, grid 64, zoom 100% -> 50%
key v; key g; key f; key 6
key minus; key minus
sleep 0.3
shot 04-empty

# ---------------------------------------------------------------- draw geometry (vertex mode)
# Room A 512x512
draw "-640 -256" "-640 256" "-128 256" "-128 -256" "-640 -256"
# corridor 256x128: starts/ends on room A's east wall (Eureka splits it)
draw "-128 -64" "128 -64" "128 64" "-128 64"
# room B 384x384: starts/ends on the corridor's east corners
draw "128 -64" "128 -192" "512 -192" "512 192" "128 192" "128 64"
key Escape
shot 05-drawn

# ---------------------------------------------------------------- sector properties (sector mode)
key s
# sector panel widgets (screen coords with the 1270-wide main window)
CEIL_TEX="1092 210"; FLOOR_TEX="1092 307"

# Room A: floor FLOOR4_8, ceiling CEIL3_5, heights 0/128 (defaults)
at -384 0; xdotool click 1; sleep 0.3
panel_set $FLOOR_TEX FLOOR4_8
panel_set $CEIL_TEX CEIL3_5
at -384 0; key ctrl+u

# Corridor: floor +16 (two steps of 8), floor FLAT20, light 176-32=144
at 0 0; xdotool click 1; sleep 0.3
key period; key period
key I; key I
panel_set $FLOOR_TEX FLAT20
panel_set $CEIL_TEX CEIL5_1
at 0 0; key ctrl+u

# Room B: floor +40 (5x8), ceiling +64 -> 192, sky ceiling, floor GRASS1, light +16
at 320 0; xdotool click 1; sleep 0.3
key period; key period; key period; key period; key period
key ctrl+bracketright
key i
panel_set $FLOOR_TEX GRASS1
panel_set $CEIL_TEX F_SKY1
at 320 0; key ctrl+u
shot 06-sectors

# ---------------------------------------------------------------- player 1 start (thing mode)
key t
at -512 0; key space                   # new thing, selected, default type 2014
THING_TYPE="1070 68"
panel_set $THING_TYPE 1                 # -> Player 1 start, angle 0 = east (toward room B)
at -512 0
shot 07-thing

# ---------------------------------------------------------------- save & quit
key ctrl+s
sleep 2
shot 08-saved
key ctrl+q
for _ in $(seq 1 100); do kill -0 "$EU_PID" 2>/dev/null || break; sleep 0.1; done
if kill -0 "$EU_PID" 2>/dev/null; then
    shot 09-quit-stuck
    die "eureka did not quit (unsaved changes dialog?); log: $TMP/eureka.log"
fi
EU_PID=""

# ---------------------------------------------------------------- result
[ -s "$NEWWAD" ] || die "Eureka did not write $NEWWAD"
head -c 4 "$NEWWAD" | grep -q PWAD || die "$NEWWAD is not a PWAD"
# read-only sanity check of what Eureka saved (catches a mis-calibrated
# screen<->map mapping or a missed key press); skipped without python3
if command -v python3 >/dev/null 2>&1; then
python3 - "$NEWWAD" <<'PY' || die "saved map does not have the expected contents (re-run with SHOTS=dir to debug)"
import struct, sys
d = open(sys.argv[1], 'rb').read()
_, n, off = struct.unpack('<4sii', d[:12])
L = {}
for i in range(n):
    pos, size, name = struct.unpack('<ii8s', d[off+16*i:off+16*i+16])
    L.setdefault(name.rstrip(b'\0').decode(), d[pos:pos+size])
V = sorted(struct.unpack_from('<hh', L['VERTEXES'], i) for i in range(0, len(L['VERTEXES']), 4))
S = [struct.unpack_from('<hh8s8sh', L['SECTORS'], i) for i in range(0, len(L['SECTORS']), 26)]
T = [struct.unpack_from('<hhhhh', L['THINGS'], i) for i in range(0, len(L['THINGS']), 10)]
two = sum(1 for i in range(0, len(L['LINEDEFS']), 14) if struct.unpack_from('<H', L['LINEDEFS'], i+4)[0] & 4)
want_v = sorted([(-640,-256),(-640,256),(-128,256),(-128,-256),(-128,-64),(-128,64),
                 (128,-64),(128,64),(128,-192),(512,-192),(512,192),(128,192)])
want_s = [(0,128,b'FLOOR4_8',b'CEIL3_5\0',176),(16,128,b'FLAT20\0\0',b'CEIL5_1\0',144),
          (40,192,b'GRASS1\0\0',b'F_SKY1\0\0',192)]
ok = (V == want_v and S == want_s and two == 2 and len(L['LINEDEFS']) == 14*14
      and T == [(-512, 0, 0, 1, 7)])
print("self-check:", "OK" if ok else "MISMATCH", f"({len(V)} vertices, {len(S)} sectors, {two} two-sided lines, {len(T)} things)")
sys.exit(0 if ok else 1)
PY
fi
mkdir -p "$(dirname "$OUT")"
cp "$NEWWAD" "$OUT"
echo "draw-map.sh: wrote $OUT ($(stat -c %s "$OUT") bytes, sha256 $(sha256sum "$OUT" | cut -c1-16)...) in $(( $(date +%s) - START_TS ))s"
