#!/usr/bin/env bash
# Keeps the repository lean (ctest `Repository.LeanDocs`, label cpu): fails when a tracked image
# anywhere in the repository is over MAX_IMAGE_KB (300) or when the tracked files under docs/ add up
# to more than MAX_DOCS_KB (5120, 5 MB). Rendered pictures (contact sheets, comparisons, judging
# kits, before/after) belong in out/, which git ignores; each docs page names the command.
#
#   bash scripts/check-lean-docs.sh [REPO_ROOT]
#
# In a git checkout it measures the files git tracks; elsewhere (a source tarball) every file.
set -euo pipefail
root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
max_image_kb=${MAX_IMAGE_KB:-300}
max_docs_kb=${MAX_DOCS_KB:-5120}
cd "$root"

if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  list() { git ls-files -z -- "$@"; }
else
  list() { find "${@:-.}" -type f -print0 2>/dev/null; }
fi

status=0
images=0 over=0
while IFS= read -r -d '' f; do
  [ -f "$f" ] || continue  # deleted in the working tree, not yet committed
  case "${f,,}" in
    *.png|*.jpg|*.jpeg|*.gif|*.webp|*.bmp|*.tga|*.tif|*.tiff|*.exr|*.hdr) ;;
    *) continue ;;
  esac
  images=$((images + 1))
  kb=$(( ($(stat -c %s "$f") + 1023) / 1024 ))
  if [ "$kb" -gt "$max_image_kb" ]; then
    echo "check-lean-docs: $f is $kb KB, over $max_image_kb KB: make it with a script into out/" >&2
    over=$((over + 1))
    status=1
  fi
done < <(list)

docs_bytes=0
while IFS= read -r -d '' f; do
  [ -f "$f" ] || continue
  docs_bytes=$((docs_bytes + $(stat -c %s "$f")))
done < <(list docs)
docs_kb=$(( (docs_bytes + 1023) / 1024 ))
if [ "$docs_kb" -gt "$max_docs_kb" ]; then
  echo "check-lean-docs: docs/ holds $docs_kb KB, over $max_docs_kb KB" >&2
  status=1
fi
echo "check-lean-docs: $images tracked images, $over over $max_image_kb KB; docs/ $docs_kb KB (limit $max_docs_kb KB)"
exit $status
