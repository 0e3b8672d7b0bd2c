#!/usr/bin/env bash
# bench/scale.sh on the three-set rock mass (bench/make_rockmass.py) at about 1e3, 1e4, 1e5 blocks.
#   bash bench/rockmass_scale.sh BLOCKDEM_BINARY WORK_DIR [blocks ...]   (default 1000 10000 100000)
exec bash "$(dirname "$0")/scale.sh" rockmass "$@"
