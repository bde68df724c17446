# Sourced by the sweep tests: writes a small sweep into folder $1 with $2 OpenMP threads per case:
# four short impacts on the built-in default scene (600 to 750 blocks, 15 to 30 m/s, 40 µs; the
# larger the mesh, the longer expected, so case4 goes first) and "too-coarse", whose run fails
# (300 blocks cannot mesh this geometry) after its scene passed the sweep's checks.
write_small_sweep() {
  local folder=$1 threads=$2 n
  local default_scene
  default_scene="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)/scenes/default.toml"
  mkdir -p "$folder"
  for n in 1 2 3 4; do
    printf 'base = "%s"\nname = "case%s"\n[mesh]\nblocks = %s\n[analysis]\nend_time = 4e-5\n[bodies.disc]\nvelocity = [0.0, -%s.0]\n' \
      "$default_scene" "$n" "$((550 + 50 * n))" "$((10 + 5 * n))" > "$folder/case$n.toml"
  done
  printf 'base = "%s"\nname = "too-coarse"\n[mesh]\nblocks = 300\n[analysis]\nend_time = 4e-5\n' \
    "$default_scene" > "$folder/too_coarse.toml"
  printf 'name = "small"\ncases = ["case1.toml", "case2.toml", "too_coarse.toml", "case3.toml", "case4.toml"]\ncrack_time = 4e-5\nthreads = %s\n' \
    "$threads" > "$folder/small.sweep.toml"
}

fail() { echo "FAIL: $*"; exit 1; }

# The files of a case's run directory but its summary (wall times) and log, in $1 and $2 alike.
same_run_files() {
  local f
  for f in $(cd "$1" && find . -type f ! -name summary.json ! -name run.log | sort); do
    cmp -s "$1/$f" "$2/$f" || fail "$2/$f differs from $1/$f"
  done
}
