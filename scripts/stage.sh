# Stage lines for the project's scripts (sourced, not run):
#
#   stage "what it does" command args...   # runs it, prints its start and its time
#   stage_summary                          # prints every stage's time
#
# Where standard output is not a terminal, a line every 30 s says which stage
# is still running (cargo hides its progress bar there).

STAGE_LINES=()

stage() {
    local name=$1
    shift
    local start=$SECONDS heartbeat=""
    echo "== $(date +%H:%M:%S) $name"
    if [ ! -t 1 ]; then
        (while sleep 30; do echo "   ... $name: $((SECONDS - start)) s"; done) &
        heartbeat=$!
    fi
    local status=0
    "$@" || status=$?
    if [ -n "$heartbeat" ]; then
        kill "$heartbeat" 2>/dev/null || true
        wait "$heartbeat" 2>/dev/null || true
    fi
    local line
    line=$(printf '%5d s  %s' $((SECONDS - start)) "$name")
    STAGE_LINES+=("$line")
    if [ $status -ne 0 ]; then
        echo "== failed after $((SECONDS - start)) s: $name (exit $status)"
        exit $status
    fi
    echo "-- $((SECONDS - start)) s: $name"
}

stage_summary() {
    echo "== stage times"
    printf '%s\n' "${STAGE_LINES[@]}"
}
