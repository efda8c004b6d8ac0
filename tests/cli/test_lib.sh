# Set-up and checks shared by the shell tests of the pmech program (tests/cli/*_test.sh,
# tests/material/material_cli_test.sh). Sourced once PMECH, SRC and WORK hold the test's arguments:
# the test then runs in an emptied WORK directory, and fail is 1 once a check has failed.
rm -rf "$WORK"; mkdir -p "$WORK"; cd "$WORK"
fail=0
# description, command...: "ok" or "FAIL" with the description, as the command succeeds or not
check() { d=$1; shift; if "$@"; then echo "ok   $d"; else echo "FAIL $d"; fail=1; fi; }
# code, description, command...: whether the command exits with code; its output left in out.txt and
# err.txt for the checks that follow (err.txt shown when the code is wrong)
expect_exit() {
  code=$1; d=$2; shift 2
  "$@" >out.txt 2>err.txt; rc=$?
  if [ "$rc" -eq "$code" ]; then echo "ok   $d (exit $rc)"; else echo "FAIL $d: exit $rc, wanted $code"; cat err.txt; fail=1; fi
}
# pattern, file: the file holds the pattern
has() { grep -q -- "$1" "$2"; }
# message: the message when every check passed; exits with fail
finish() { if [ $fail -eq 0 ]; then echo "$1"; fi; exit $fail; }
