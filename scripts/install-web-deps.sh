#!/usr/bin/env bash
# Installs what the command-center page and its browser tests need (called by
# scripts/install-deps.sh): Debian's chromium (the tests drive it; Playwright
# never downloads a browser), Node.js and npm when the machine has none, and the
# page's npm packages pinned in web/package-lock.json (Leaflet, @playwright/test)
# with `npm ci`, again only when the lockfile changed since the last install.
set -euo pipefail
cd "$(dirname "$0")/.."

missing=()
dpkg-query -W -f='${Status}' chromium 2>/dev/null | grep -q 'install ok installed' || missing+=(chromium)
command -v npm >/dev/null 2>&1 || missing+=(nodejs npm)
if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" -ne 0 ]; then
    echo "install-web-deps: missing packages: ${missing[*]}; run this script as root" >&2
    exit 1
  fi
  echo "install-web-deps: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

stamp=web/node_modules/.fireswarm-package-lock.json
if ! cmp -s web/package-lock.json "$stamp"; then
  echo "install-web-deps: npm ci in web/"
  # Without the npm registry (no network, or a proxy whose certificate npm does
  # not trust) the C++ still builds and its tests still run: say so loudly and go
  # on; the browser test is then not registered (web/CMakeLists.txt says why).
  if (cd web && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund --loglevel=error); then
    cp web/package-lock.json "$stamp"
  else
    echo "install-web-deps: WARNING: npm ci failed in web/ (see above): the page has no" \
         "map library and the browser tests will not run until it succeeds" >&2
  fi
fi
