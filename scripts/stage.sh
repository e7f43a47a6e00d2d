# Sourced by scripts/setup.sh, scripts/test.sh and .ci/run: `stage NAME`
# prints "== NAME" and, for the stage before it, how long it took;
# `stage_end` closes the last one and prints every stage's time.
_stage_name=""
_stage_start=$SECONDS
_stage_log=()
stage_end() {
  if [[ -n $_stage_name ]]; then
    local took=$((SECONDS - _stage_start))
    echo "== $_stage_name: ${took} s"
    _stage_log+=("$(printf '%6d s  %s' "$took" "$_stage_name")")
  fi
  _stage_name=""
}
stage() {
  stage_end
  _stage_name=$1
  _stage_start=$SECONDS
  echo "== $1"
}
stage_summary() {
  stage_end
  echo "== stage times ($1)"
  printf '%s\n' "${_stage_log[@]}"
}
# On a failure the times so far are printed too (set -e leaves before the
# script's own stage_summary).
trap '_rc=$?; ((_rc == 0)) || stage_summary "up to the failure (exit $_rc)"' EXIT
