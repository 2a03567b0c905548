#!/bin/sh
# Runs a command under Xvfb on a display number no X server in this network namespace uses.
# `xvfb-run -a` only looks for /tmp/.X<n>-lock, but a server of another container or session
# that shares the network (abstract socket @/tmp/.X11-unix/X<n>; :99 on our CI host) leaves no
# lock file here, and Xvfb then cannot listen on that number.
n=$(( 1000 + $$ % 8000 ))
while grep -q "/tmp/.X11-unix/X$n\$" /proc/net/unix 2>/dev/null || [ -e "/tmp/.X$n-lock" ]; do
  n=$(( n + 1 ))
done
exec xvfb-run -a -n "$n" -s "-screen 0 1280x1024x24" "$@"
