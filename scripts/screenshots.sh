#!/usr/bin/env bash
# The CAM tab used like a user in a real Blender window, with screenshots of every workflow.
#
# Optional and heavy (about 2 GB, several minutes; run as root): Debian trixie's Blender 4.3
# (Python 3.13) in a debootstrap chroot, Xvfb with Mesa software GL, the built linux extension
# zip installed the way a user installs it. First batch writes the demo (blender -b ... batch.py
# demo); then scripts/screenshot_driver.py drives the window with simulated mouse and key events
# (--enable-event-simulate): CAM tab, job picker, Generate, Export through the file browser, the
# written files compared with batch's, Simulate, Esc; the label-width check against the real
# sidebar. Screenshots go to build/screenshots; into docs/screenshots only with --update-docs.
#
#   sudo scripts/screenshots.sh [--update-docs] [CHROOT_DIR]        (default: build/trixie)
set -euo pipefail
cd "$(dirname "$0")/.."
REPO=$(pwd)
UPDATE_DOCS=0
if [ "${1:-}" = --update-docs ]; then UPDATE_DOCS=1; shift; fi
CHROOT=${1:-$REPO/build/trixie}
MIRROR=${MIRROR:-http://deb.debian.org/debian}

if [ ! -e "$CHROOT/usr/bin/xdotool" ] || [ ! -e "$CHROOT/usr/bin/blender" ]; then
  command -v debootstrap >/dev/null || apt-get install -y -q debootstrap
  [ -d "$CHROOT/usr" ] || debootstrap --variant=minbase trixie "$CHROOT" "$MIRROR"
  chroot "$CHROOT" apt-get update -q
  DEBIAN_FRONTEND=noninteractive chroot "$CHROOT" apt-get install -y -q --no-install-recommends \
    blender xvfb xauth x11-apps xdotool imagemagick libgl1-mesa-dri libegl1 libegl-mesa0 python3-numpy \
    fonts-dejavu-core
fi

./scripts/setup.sh --demo
.venv/bin/python scripts/build_extension.py --platforms linux-x64 --out build/dist
ZIP=$(ls build/dist/kezuri-*-linux_x64.zip | tail -n 1)
cp "$ZIP" "$CHROOT/tmp/kezuri.zip"
cp scripts/screenshot_driver.py tests/sidebar_fit.py "$CHROOT/tmp/"

mountpoint -q "$CHROOT/proc" || mount -t proc proc "$CHROOT/proc"
mountpoint -q "$CHROOT/dev" || mount --bind /dev "$CHROOT/dev"
trap 'umount "$CHROOT/dev" "$CHROOT/proc" 2>/dev/null || true' EXIT

run() { chroot "$CHROOT" env HOME=/root LIBGL_ALWAYS_SOFTWARE=1 "$@"; }
run rm -rf /root/.config/blender /tmp/screenshots /tmp/kezuri-exports /tmp/blender-demo
run blender --command extension install-file -r user_default -e /tmp/kezuri.zip
run blender -b --python-expr \
  "import bpy; bpy.context.preferences.view.show_splash = False; bpy.ops.wm.save_userpref()"

# Batch first, with the same Blender: the files the window's exports are compared with.
rm -rf "$CHROOT/tmp/repo" && mkdir -p "$CHROOT/tmp/repo"
git ls-files -z | xargs -0 tar -cf - | tar -x -C "$CHROOT/tmp/repo"
run blender -b --python /tmp/repo/batch.py -- demo --out /tmp/blender-demo 2>&1 | grep -E "wrote|kezuri:" || true

LOG=$REPO/build/screenshots.log
mkdir -p build
run xvfb-run -a -s "-screen 0 1600x1000x24" env KEZURI_SCREENSHOTS=/tmp/screenshots \
  KEZURI_BATCH=/tmp/blender-demo KEZURI_EXPORTS=/tmp/kezuri-exports \
  blender --enable-event-simulate --python /tmp/screenshot_driver.py 2>&1 \
  | grep -E "^(screenshot|click|export|fit|modal|japanese|stepnc|failed|done)|Error" | tee "$LOG" || true

rm -rf build/screenshots && mkdir -p build/screenshots
cp "$CHROOT"/tmp/screenshots/*.png build/screenshots/ 2>/dev/null || true
ls -l build/screenshots
if [ "$UPDATE_DOCS" = 1 ]; then
  cp build/screenshots/*.png docs/screenshots/
  echo "copied into docs/screenshots"
fi
# The run passed only if the driver got to its end (a crashed Blender prints no "failed")
grep -q "^done" "$LOG" || { echo "the real-window run did not finish (Blender crashed? see $LOG)"; exit 1; }
! grep -q "^failed" "$LOG"
