#!/usr/bin/env bash
# Installs what is missing (Debian 12), builds everything and runs the whole test suite.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
start=$(date +%s)
obscura_setup
obscura_build -DOBSCURA_BUILD_TESTS=ON -DOBSCURA_BUILD_EXAMPLES=ON -DOBSCURA_BUILD_CLI=ON
cd "$OBSCURA_BUILD_DIR"
status=0
ctest --output-on-failure --parallel "$OBSCURA_JOBS" --timeout 900 || status=$?
echo "scripts/test.sh: $(( $(date +%s) - start )) s in all, ctest exit status $status"
exit $status
