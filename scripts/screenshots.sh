#!/usr/bin/env bash
# Screenshots of every Kezuri panel in a real Blender window, into docs/screenshots/.
#
# Optional and heavy (about 2 GB, several minutes; run as root): Debian trixie's Blender 4.3
# (Python 3.13) in a debootstrap chroot, Xvfb with Mesa software GL, the built linux extension
# zip installed the way a user installs it, the UI driven by scripts/screenshot_driver.py.
#
#   sudo scripts/screenshots.sh [CHROOT_DIR]        (default: build/trixie)
set -euo pipefail
cd "$(dirname "$0")/.."
REPO=$(pwd)
CHROOT=${1:-$REPO/build/trixie}
MIRROR=${MIRROR:-http://deb.debian.org/debian}

if [ ! -e "$CHROOT/usr/lib/x86_64-linux-gnu/libEGL.so.1" ]; then
  command -v debootstrap >/dev/null || apt-get install -y -q debootstrap
  [ -d "$CHROOT/usr" ] || debootstrap --variant=minbase trixie "$CHROOT" "$MIRROR"
  chroot "$CHROOT" apt-get update -q
  DEBIAN_FRONTEND=noninteractive chroot "$CHROOT" apt-get install -y -q --no-install-recommends \
    blender xvfb xauth x11-apps xdotool imagemagick libgl1-mesa-dri libegl1 libegl-mesa0 python3-numpy \
    fonts-dejavu-core
fi

./scripts/setup.sh
.venv/bin/python scripts/build_extension.py --platforms linux-x64 --out build/dist
ZIP=$(ls build/dist/kezuri-*-linux_x64.zip | tail -n 1)
cp "$ZIP" "$CHROOT/tmp/kezuri.zip"
cp scripts/screenshot_driver.py "$CHROOT/tmp/screenshot_driver.py"

mountpoint -q "$CHROOT/proc" || mount -t proc proc "$CHROOT/proc"
mountpoint -q "$CHROOT/dev" || mount --bind /dev "$CHROOT/dev"
trap 'umount "$CHROOT/dev" "$CHROOT/proc" 2>/dev/null || true' EXIT

run() { chroot "$CHROOT" env HOME=/root LIBGL_ALWAYS_SOFTWARE=1 "$@"; }
run rm -rf /root/.config/blender /tmp/screenshots
run blender --command extension install-file -r user_default -e /tmp/kezuri.zip
run blender -b --python-expr \
  "import bpy; bpy.context.preferences.view.show_splash = False; bpy.ops.wm.save_userpref()"
run xvfb-run -a -s "-screen 0 1600x1000x24" env KEZURI_SCREENSHOTS=/tmp/screenshots \
  blender --python /tmp/screenshot_driver.py 2>&1 | grep -E "screenshot|failed|Error|modal|japanese" || true

mkdir -p docs/screenshots
cp "$CHROOT"/tmp/screenshots/*.png docs/screenshots/
ls -l docs/screenshots

# The same Blender in batch mode: blender -b --python batch.py -- demo, on the installed wheels.
rm -rf "$CHROOT/tmp/repo" && mkdir -p "$CHROOT/tmp/repo"
git ls-files -z | xargs -0 tar -cf - | tar -x -C "$CHROOT/tmp/repo"
run blender -b --python /tmp/repo/batch.py -- demo --out /tmp/blender-demo 2>&1 | grep -E "wrote|kezuri:" || true
