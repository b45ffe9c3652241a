# Sourced by the scripts that start programs of their own (a throwaway X
# server, a window manager, a provider): a work folder, and on exit every
# program they started stopped by PID (newest first, so an X server goes
# last) and the folder removed. Sets `work` and `pids`; gives `spawn`,
# `stop` and `wait_for`.
pids=()  # newest first
work=$(mktemp -d)
background_cleanup() {
    for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
    for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
    # A browser's helpers may still write into its profile for a moment
    # after the browser itself is gone: try again rather than fail the run.
    local tries
    for tries in 1 2 3 4 5 6 7 8 9 10; do
        rm -rf "$work" 2>/dev/null && return 0
        sleep 0.5
    done
    echo "could not remove $work" >&2
    return 0
}
trap background_cleanup EXIT
trap 'exit 130' INT TERM

# Starts a program in the background and remembers its PID.
spawn() {
    "$@" &
    pids=("$!" "${pids[@]}")
}
# Stops one program this script started.
stop() {
    local pid=$1 kept=() p
    kill "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
    for p in "${pids[@]}"; do [[ $p == "$pid" ]] || kept+=("$p"); done
    pids=("${kept[@]}")
}
# Waits up to $2 seconds (default 10) for the command $1 to succeed.
wait_for() {
    local what=$1 limit=${2:-10} i
    for ((i = 0; i < limit * 20; ++i)); do
        eval "$what" >/dev/null 2>&1 && return 0
        sleep 0.05
    done
    return 1
}
