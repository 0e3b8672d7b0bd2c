#!/usr/bin/env bash
# bench/scale.sh on the brick pile (bench/make_pile.py) at about 1e3, 1e4, 1e5 blocks.
#   bash bench/pile_scale.sh BLOCKDEM_BINARY WORK_DIR [n ...]     (default n: 10 32 100)
exec bash "$(dirname "$0")/scale.sh" pile "$@"
