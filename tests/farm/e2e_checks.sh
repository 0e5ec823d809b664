# Checks shared by the farm end-to-end tests (ninja_e2e.sh, slurm_e2e.sh);
# sourced, not run. The caller defines:
#   fail MESSAGE   report a failure and exit 1
#   $skybake       the skybake executable
#   $here          this folder (make_catalog.sh lives here)
#   $T             the test's scratch folder

# Every baked file (outputs, stamps) is byte-identical between two output
# folders (manifests included), the same files exist in both; the bake logs
# hold times and are not compared. Ninja's own files and the lock file are not compared.
same_outputs() {
  local a="$1" b="$2" f la lb
  la="$(cd "$a" && find . -type f ! -name '.ninja_*' ! -name .skybake.lock | sort)"
  lb="$(cd "$b" && find . -type f ! -name '.ninja_*' ! -name .skybake.lock | sort)"
  [ -n "$la" ] || fail "$a is empty"
  [ "$la" = "$lb" ] || fail "different files in '$a' and '$b':
$(diff <(echo "$la") <(echo "$lb") || true)"
  while IFS= read -r f; do
    case "$f" in
      */bake_log.json) ;;  # times and file times differ by nature
      *) cmp -s "$a/$f" "$b/$f" || fail "not byte-identical: $a/$f $b/$f" ;;
    esac
  done <<<"$la"
}

# Edges ninja ran, from its status lines "[i/n] bake scene/product".
edges_run() { grep -cE '^\[[0-9]+/[0-9]+\] bake ' <<<"$1" || true; }

# A registered product that reads another one (multiscattering, skyview, ...):
# the first whose probe scene {transmittance, P} gives an edge in plan --json.
find_dependent_product() {
  local p probe="$T/probe" products help plan
  help="$("$skybake" --help)"
  products="$(awk '/^Products:/ { on = 1; next } on && NF == 0 { exit } on { print $1 }' <<<"$help")"
  # Cheapest first when registered.
  for p in multiscattering skyview $products; do
    [ "$p" != transmittance ] && grep -qx "$p" <<<"$products" || continue
    rm -rf "$probe"
    "$here/make_catalog.sh" -p "transmittance,$p" -s 64x16 1 "$probe" >/dev/null
    plan="$("$skybake" plan "$probe" -o "$probe/out" --json 2>/dev/null)" || continue
    if grep -q '"edges": \[$' <<<"$plan"; then
      echo "$p"
      return
    fi
  done
}
