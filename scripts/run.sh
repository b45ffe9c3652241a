#!/usr/bin/env bash
# The main job: the provider. Without a display it runs headless, showing the
# built-in demo board on a virtual 1920 x 1080 screen. It listens on every
# address so a phone or webcam on the network can reach it (pairing and TLS
# keep strangers out); UMF_BIND=127.0.0.1 keeps it on this machine.
# Extra arguments go to umf-provider (for example --board BOARD.json).
set -euo pipefail
build=${1:-build/release}
shift || true
exec "$build/bin/umf-provider" serve --bind "${UMF_BIND:-0.0.0.0}" "$@"
