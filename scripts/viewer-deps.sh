# Sourced by the scripts that render trees (compare-trees.sh, blind-pairs.sh, blender-sheet.sh).
#   apt_install_missing TAG PACKAGE...   installs the Debian packages given (apt-get as root, sudo
#                                        otherwise), saying so under TAG; nothing when none is given
#   viewer_deps TAG VIEWER_DIR           Debian chromium, imagemagick, node, npm and fonts when
#                                        missing, then `npm ci` in the viewer when its packages are
#                                        (three, ez-tree, playwright-core; no browser download)
apt_install_missing() {
  local tag=$1; shift
  [ $# -gt 0 ] || return 0
  echo "$tag: installing $*" >&2
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo=sudo
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "$@" >/dev/null
}

viewer_deps() {
  local tag=$1 viewer=$2 need=()
  [ -x "${SYLVA_CHROMIUM:-/usr/bin/chromium}" ] || need+=(chromium)
  command -v montage >/dev/null 2>&1 || need+=(imagemagick)
  command -v node >/dev/null 2>&1 || need+=(nodejs)
  command -v npm >/dev/null 2>&1 || need+=(npm)
  fc-list 2>/dev/null | grep -qi dejavu || need+=(fonts-dejavu-core)
  apt_install_missing "$tag" "${need[@]}"
  if [ ! -f "$viewer/node_modules/three/package.json" ] \
    || [ ! -f "$viewer/node_modules/@dgreenheck/ez-tree/package.json" ] \
    || [ ! -f "$viewer/node_modules/playwright-core/package.json" ]; then
    echo "$tag: npm ci in tools/viewer" >&2
    (cd "$viewer" && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund --loglevel=error >/dev/null)
  fi
}
