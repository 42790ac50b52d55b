#!/bin/sh
# The load benchmark of issue 17 (docs/performance.md, "Web service under load"): builds the
# release `platener` and `platener-load`, then runs `platener-load bench` with the given flags
# (default: 10, 100 and 500 clients on SQLite and on a throwaway PostgreSQL cluster).
#   tools/load-bench.sh
#   tools/load-bench.sh --clients 10,100 --database sqlite
set -eu
cd "$(dirname "$0")/.."
cargo build --release -p platener-cli -p platener-testpg --bins
exec target/release/platener-load bench "$@"
