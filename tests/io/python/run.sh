#!/bin/sh
# Runs the fixture program ($1), then the Python check ($2) on what it wrote, in the current directory, with the
# first of $SSS_PYTHON, python3 on the PATH and /usr/bin/python3 that imports numpy. Exit status 77 (skipped, for
# CTest's SKIP_RETURN_CODE and Meson) when none does.
for py in "${SSS_PYTHON:-}" python3 /usr/bin/python3; do
    [ -n "$py" ] && command -v "$py" >/dev/null 2>&1 && "$py" -c "import numpy" >/dev/null 2>&1 && {
        "$1" || exit 1
        exec "$py" "$2"
    }
done
echo "no python3 with numpy found (Debian: python3-numpy): skipped"
exit 77
