# Sourced by the build and test scripts: `stage NAME COMMAND...` runs COMMAND and prints how long
# it took ("stage: NAME: N s"); .ci/run collects these lines into its summary, so that CI's time
# (limited to 90 minutes) can be followed stage by stage. The lines also go to the file named by
# BLOCKDEM_STAGE_TIMES when it is set.
stage() {
  local name=$1 start status=0
  shift
  start=$(date +%s)
  "$@" || status=$?
  local line
  line="$name: $(( $(date +%s) - start )) s"
  [ "$status" -eq 0 ] || line="$line (failed, exit $status)"
  echo "stage: $line"
  if [ -n "${BLOCKDEM_STAGE_TIMES:-}" ]; then echo "$line" >> "$BLOCKDEM_STAGE_TIMES"; fi
  return "$status"
}
