#!/usr/bin/env bash
# Mutation testing with cargo-mutants (https://mutants.rs), configured in
# .cargo/mutants.toml: plant small bugs (an operator flipped, a return value
# replaced) one at a time in the library's core and check that a test fails.
# See docs/DEVELOPING.md, "Mutation testing".
#
#   scripts/mutants.sh                   the core code this branch changed
#                                        against main (cargo mutants --in-diff)
#   scripts/mutants.sh --base BRANCH     ... against BRANCH
#   scripts/mutants.sh --file PATH       every mutant of one core file
#                                        (repeat --file for several files)
#   scripts/mutants.sh --tests FILTER    run only the tests whose names
#                                        contain FILTER (e.g. `mpc::`; the
#                                        library's unit tests and the
#                                        integration crate use the module's
#                                        name), for speed; repeat --tests
#                                        for several filters (a test runs
#                                        when its name contains any)
#   scripts/mutants.sh --skip FILTER     leave out the tests whose names
#                                        contain FILTER (repeatable; e.g.
#                                        ones that hold only in release)
#   scripts/mutants.sh --lib ...         the library's unit tests only (no
#                                        integration crate: one link step
#                                        less per mutant)
#   scripts/mutants.sh --list ...        list the mutants, build nothing
#
# Any other argument goes to cargo mutants (e.g. --in-place, --timeout 600).
# The results are in mutants.out/ (outcomes.json, caught.txt, missed.txt,
# timeout.txt, unviable.txt). Needs `cargo install --locked cargo-mutants`.
set -euo pipefail
cd "$(dirname "$0")/.."

base=main
files=()
tests=()
skips=()
lib_only=""
extra=()
while (($#)); do
    case "$1" in
        --base) base="$2"; shift 2 ;;
        --file) files+=("$2"); shift 2 ;;
        --tests) tests+=("$2"); shift 2 ;;
        --skip) skips+=("$2"); shift 2 ;;
        --lib) lib_only=1; shift ;;
        *) extra+=("$1"); shift ;;
    esac
done

if ! cargo mutants --version >/dev/null 2>&1; then
    echo "cargo-mutants is not installed: cargo install -j 1 --locked cargo-mutants" >&2
    exit 2
fi

# The config, scoped: with --file its core globs are replaced by that one
# file (a command-line --file would add to the config's globs); with
# --tests the test filter joins the config's test arguments (cargo-mutants
# puts the config's `additional_cargo_test_args` after the command line's,
# so a filter given as `-- -- FILTER` would land before `--lib`).
mkdir -p target
scoped=target/mutants-scoped.toml
cp .cargo/mutants.toml "$scoped"
if ((${#files[@]})); then
    globs=""
    for file in "${files[@]}"; do
        if [[ ! -f "$file" ]]; then
            echo "--file: no such file: $file" >&2
            exit 2
        fi
        globs+="${globs:+, }\"$file\""
    done
    {
        echo "examine_globs = [$globs]"
        sed '/^examine_globs = \[/,/^\]/d' .cargo/mutants.toml
    } >"$scoped"
fi
if [[ -n "$lib_only" ]]; then
    sed -i 's|^additional_cargo_test_args = \["--lib", "--test", "it"|additional_cargo_test_args = ["--lib"|' "$scoped"
    grep -q '^additional_cargo_test_args = \["--lib"\]' "$scoped" || {
        echo "--lib: .cargo/mutants.toml's test arguments are not [\"--lib\", \"--test\", \"it\"]" >&2
        exit 2
    }
fi
if ((${#tests[@]} + ${#skips[@]})); then
    filters=""
    for filter in "${tests[@]}"; do
        filters+=", \"$filter\""
    done
    for filter in "${skips[@]}"; do
        filters+=", \"--skip\", \"$filter\""
    done
    sed -i "s|^additional_cargo_test_args = \[\(.*\)\]|additional_cargo_test_args = [\1, \"--\"$filters]|" "$scoped"
fi
# A release build of armkit takes minutes on a loaded 2-core machine; a
# multiple of the baseline's build time is no bound (the baseline may find
# the build fresh).
args=(--config "$scoped" --build-timeout 1200)
if ((${#files[@]} == 0)); then
    if ! git rev-parse --verify --quiet "$base" >/dev/null; then
        echo "--base: no such branch or commit: $base" >&2
        exit 2
    fi
    diff=target/mutants.diff
    git diff "$(git merge-base "$base" HEAD)" -- crates/armkit/src >"$diff"
    if [[ ! -s "$diff" ]]; then
        echo "no change to crates/armkit/src against $base: nothing to mutate"
        exit 0
    fi
    args+=(--in-diff "$diff")
fi

exec cargo mutants "${args[@]}" "${extra[@]}"
