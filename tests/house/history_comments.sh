#!/usr/bin/env bash
# Source comments say why, or cite docs/ and the papers; they never narrate
# how the code got here or on which machine it was measured (docs/testing.md,
# house rules). Lists each line of src/ and runtime/ that does, exit 1 if any.
# Usage: history_comments.sh REPO_DIR
set -euo pipefail
repo="${1:?usage: history_comments.sh REPO_DIR}"
pattern='development machine|this machine|(third|fourth|fifth|sixth) pass\b|this round|last round|this session|previous session|earlier session|load average|used to be|\.\./shared|issue #?[0-9]+'
if grep -rn -i -E "$pattern" "$repo/src" "$repo/runtime"; then
  echo "history_comments: the lines above narrate history, machines or issues" >&2
  exit 1
fi
