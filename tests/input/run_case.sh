#!/usr/bin/env bash
# Runs one case of cases.txt through the real `sonarsim render` and checks the answer to bad input:
# the exit status, exactly one line on stderr containing the expected fragment, and that the output
# directory is as it was (no file created, the existing outputs neither truncated nor replaced).
# Usage: run_case.sh SONARSIM CASES_FILE WORK_DIR CASE_ID     (exit 77: skipped)
set -uo pipefail
sonarsim=$1 cases=$2 work=$3 id=$4
here=$(cd "$(dirname "$cases")" && pwd)

line=$(grep -E "^${id} *\|" "$cases" | head -n 1)
[ -n "$line" ] || { echo "no case '$id' in $cases"; exit 1; }
IFS='|' read -r _ want_status fragment setup args <<<"$line"
trim() { local s=$1; s=${s#"${s%%[![:space:]]*}"}; printf '%s' "${s%"${s##*[![:space:]]}"}"; }
want_status=$(trim "$want_status") fragment=$(trim "$fragment") setup=$(trim "$setup") args=$(trim "$args")

rm -rf "$work" && mkdir -p "$work/out" || exit 1
work=$(cd "$work" && pwd)
# Outputs of an earlier run: a failed render must leave them exactly as they are.
echo "earlier image" >"$work/out/img.png"
echo "earlier metadata" >"$work/out/img.json"

as_user=()
need_unprivileged() { # root reads and writes everything: drop to nobody for permission cases
    [ "$(id -u)" -ne 0 ] && return 0
    command -v setpriv >/dev/null || { echo "SKIP: running as root without setpriv"; exit 77; }
    as_user=(setpriv --reuid=65534 --regid=65534 --clear-groups --)
    "${as_user[@]}" test -x "$sonarsim" -a -r "$cases" ||
        { echo "SKIP: user nobody cannot reach $sonarsim or $cases"; exit 77; }
    chmod 755 "$work"
    chmod 777 "$work/out"
}
case "$setup" in
-) ;;
dir:*) mkdir -p "$work/${setup#dir:}" ;;
unreadable:*) # unreadable:SRC:NAME  copies SRC to WORK/NAME without read permission
    spec=${setup#unreadable:}
    cp "$here/${spec%%:*}" "$work/${spec#*:}" && chmod 000 "$work/${spec#*:}"
    need_unprivileged ;;
sparse:*) # sparse:NAME:SIZE  a file of SIZE bytes (of zeros, sparse)
    spec=${setup#sparse:}
    truncate -s "${spec#*:}" "$work/${spec%%:*}" ;;
readonly-out)
    need_unprivileged
    chmod 555 "$work/out" ;;
*) echo "unknown setup '$setup'"; exit 1 ;;
esac

# MESH=path stands for a scene whose only object is that mesh (resolved from tests/input).
args=${args//@WORK@/$work} fragment=${fragment//@WORK@/$work}
if [[ $args =~ MESH=([^ ]+) ]]; then
    mesh=${BASH_REMATCH[1]}
    [[ $mesh = /* ]] || mesh="$here/$mesh"
    printf '{"objects": [{"mesh": "%s", "position": [1.5, 1.5, 0.1]}]}\n' "$mesh" >"$work/scene.json"
    chmod 644 "$work/scene.json"
    args=${args/MESH=${BASH_REMATCH[1]}/--scene $work/scene.json}
fi
eval "set -- $args"
[[ " $* " == *" --out "* ]] || set -- "$@" --out "$work/out/img"

cd "$here" || exit 1
before=$(cd "$work/out" && ls -A | sort && cat img.png img.json 2>/dev/null)
"${as_user[@]}" "$sonarsim" render "$@" >"$work/stdout" 2>"$work/stderr"
status=$?
chmod -R u+rwX "$work" 2>/dev/null
after=$(cd "$work/out" && ls -A | sort && cat img.png img.json 2>/dev/null)

fail=0
report() { echo "FAIL [$id]: $*"; fail=1; }
[ "$status" = "$want_status" ] || report "exit status $status, expected $want_status"
if [ "$want_status" = 0 ]; then
    for f in img.png img_polar.png img.npy img.json; do [ -s "$work/out/$f" ] || report "no $f written"; done
    grep -qF -- "$fragment" "$work/stdout" || report "stdout lacks '$fragment'"
else
    [ "$(wc -l <"$work/stderr")" = 1 ] || report "stderr is not exactly one line"
    grep -qF -- "$fragment" "$work/stderr" || report "stderr lacks '$fragment'"
    [ "$before" = "$after" ] || report "the output directory changed: $(cd "$work/out" && ls -A | tr '\n' ' ')"
fi
echo "args:   $*"
echo "stderr: $(cat "$work/stderr")"
exit $fail
