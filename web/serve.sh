#!/usr/bin/env bash
# Builds the web demo and serves it on http://127.0.0.1:PORT/ (default 8421) until
# Ctrl-C. Static files only: any static host can serve web/dist as it is.
set -euo pipefail
cd "$(dirname "$0")"
port=${1:-8421}
bash build.sh
echo "hodr web demo: open http://127.0.0.1:$port/ (Ctrl-C stops)"
exec python3 -m http.server "$port" --bind 127.0.0.1 --directory dist
