#!/usr/bin/env bash
# The editor in a real X window: opens a copy of graphs/shaded_surface.ron under Xvfb, clicks
# the `surface` node with xdotool, types a new iso value into its Inspector field, right-clicks
# empty canvas and types "silh" + Enter into the add-node palette, saves with Ctrl+S and passes
# when the saved file holds the new value and the new Silhouette node. The editor writes where its nodes
# and parameter widgets are (HATCHERY_EDITOR_LAYOUT) so the clicks land on them.
#
# Needs Xvfb and xdotool (scripts/install-deps.sh installs them) and the editor binary (built
# here if missing; HATCHERY_EDITOR_BIN overrides its path).
set -euo pipefail
cd "$(dirname "$0")/.."

for tool in Xvfb xdotool; do
    command -v "$tool" >/dev/null || { echo "editor-smoke: $tool is missing (run scripts/install-deps.sh)" >&2; exit 1; }
done
bin=${HATCHERY_EDITOR_BIN:-target/release/hatchery-editor}
if [ ! -x "$bin" ]; then
    cargo build --release -p hatchery-editor
fi

work=$(mktemp -d)
xvfb_pid=""
editor_pid=""
cleanup() {
    [ -n "$editor_pid" ] && kill "$editor_pid" 2>/dev/null || true
    [ -n "$xvfb_pid" ] && kill "$xvfb_pid" 2>/dev/null || true
    rm -rf "$work"
}
trap cleanup EXIT
fail() {
    echo "editor-smoke: FAILED: $*" >&2
    echo "--- editor log" >&2
    tail -n 30 "$work/editor.log" >&2 || true
    exit 1
}

cp graphs/shaded_surface.ron "$work/graph.ron"
layout="$work/layout.txt"

# A free display number.
display=99
while [ -e "/tmp/.X11-unix/X$display" ] || [ -e "/tmp/.X$display-lock" ]; do display=$((display + 1)); done
Xvfb ":$display" -screen 0 1600x1000x24 -nolisten tcp >"$work/xvfb.log" 2>&1 &
xvfb_pid=$!
export DISPLAY=":$display"
# Xvfb can take seconds to accept clients on a busy machine (a CI run once started the editor
# before it did: "Failed to open connection to X server"): wait up to 30 s, and say so if not.
xvfb_up=""
for _ in $(seq 300); do
    if xdotool getmouselocation >/dev/null 2>&1; then xvfb_up=1; break; fi
    kill -0 "$xvfb_pid" 2>/dev/null || break
    sleep 0.1
done
if [ -z "$xvfb_up" ]; then
    echo "editor-smoke: FAILED: Xvfb :$display did not accept connections within 30 s" >&2
    cat "$work/xvfb.log" >&2 || true
    exit 1
fi

# Its own settings folder: views and panel widths saved by earlier runs must not move things.
HATCHERY_EDITOR_LAYOUT="$layout" XDG_CONFIG_HOME="$work/config" "$bin" "$work/graph.ron" \
    >"$work/editor.log" 2>&1 &
editor_pid=$!

# Waits until the layout file has a line starting with $1 that stays the same for half a second
# (the canvas frames the graph again once every node has been drawn, so a node's first place
# may not be its last); prints its centre / right part.
wait_for() {
    local name=$1 what=$2 previous=""
    for _ in $(seq 600); do
        kill -0 "$editor_pid" 2>/dev/null || fail "the editor exited"
        if [ -f "$layout" ]; then
            local line
            line=$(grep "^$name " "$layout" || true)
            if [ -n "$line" ] && [ "$line" != "$previous" ]; then
                previous=$line
                sleep 0.5
                continue
            fi
            if [ -n "$line" ]; then
                # shellcheck disable=SC2086
                set -- $line
                case $what in
                    title) echo "$(( ($2 + $4) / 2 )) $(( $3 + 12 ))" ;;
                    right) echo "$(( $4 - 12 )) $(( ($3 + $5) / 2 ))" ;;
                esac
                return 0
            fi
        fi
        sleep 0.1
    done
    fail "$name never appeared on screen"
}

window=""
for _ in $(seq 300); do
    window=$(xdotool search --name "hatchery editor" 2>/dev/null | head -n 1 || true)
    [ -n "$window" ] && break
    kill -0 "$editor_pid" 2>/dev/null || fail "the editor exited"
    sleep 0.1
done
[ -n "$window" ] || fail "no editor window"

click() {
    xdotool mousemove --window "$window" "$1" "$2"
    sleep 0.3
    xdotool click 1
    sleep 0.5
}

# 1. Click the surface node (its title bar).
read -r x y < <(wait_for node:surface title)
# Without a window manager nothing gives the window the keyboard: give it (once it is mapped).
for _ in $(seq 50); do
    xdotool windowfocus --sync "$window" 2>/dev/null && break
    sleep 0.1
done
click "$x" "$y"
# 2. The Inspector shows its parameters: click the iso field, replace the text, Enter.
read -r x y < <(wait_for param:iso right)
click "$x" "$y"
xdotool key ctrl+a
xdotool type --delay 50 "0.25"
xdotool key Return
sleep 0.5
# 3. Right-click empty canvas, type a kind's name at once, Enter: the palette adds it.
read -r x y < <(wait_for canvas:empty title)
xdotool mousemove --window "$window" "$x" "$((y - 12))"
sleep 0.3
xdotool click 3
sleep 0.5
xdotool type --delay 50 "silh"
sleep 0.3
xdotool key Return
sleep 0.5
# 4. Save.
xdotool key ctrl+s
for _ in $(seq 50); do
    grep -q '"iso": 0.25' "$work/graph.ron" && grep -q 'kind: "Silhouette"' "$work/graph.ron" && break
    sleep 0.1
done
grep -q '"iso": 0.25' "$work/graph.ron" || fail "the saved graph does not have iso 0.25:
$(grep -n iso "$work/graph.ron")"
grep -q 'kind: "Silhouette"' "$work/graph.ron" || fail "the saved graph has no Silhouette node added from the palette:
$(grep -n kind "$work/graph.ron")"
echo "editor-smoke: ok (clicked a node, set iso = 0.25 in the Inspector, right-clicked the canvas, typed silh + Enter to add a Silhouette, saved)"
