#!/usr/bin/env bash
# Runs a command that loads the Vulkan driver with LeakSanitizer off (scripts/sanitize.sh turns it
# on): lavapipe, not built with the sanitizers, leaves a few hundred bytes at exit in a module
# already unloaded, which no suppression can name. What meadow leaks on the device is found by the
# validation layer instead (objects still alive at vkDestroyDevice), so such commands run with
# --validation. Outside the sanitizer build this changes nothing.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"
exec "$@"
