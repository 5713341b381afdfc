#!/usr/bin/env bash
# The cores this machine lets us use: nproc (the affinity mask), capped by a
# container's CPU quota (cgroup v2 cpu.max or v1 cfs_quota_us), which nproc
# does not see. make's JOBS defaults to it, so ctest -j and the builds do not
# start more work than the quota can run.
set -u
cores=$(nproc 2>/dev/null || echo 2)
quota="" period=""
if [ -r /sys/fs/cgroup/cpu.max ]; then
  read -r quota period < /sys/fs/cgroup/cpu.max
elif [ -r /sys/fs/cgroup/cpu/cpu.cfs_quota_us ] && [ -r /sys/fs/cgroup/cpu/cpu.cfs_period_us ]; then
  quota=$(cat /sys/fs/cgroup/cpu/cpu.cfs_quota_us)
  period=$(cat /sys/fs/cgroup/cpu/cpu.cfs_period_us)
fi
if [[ "$quota" =~ ^[0-9]+$ && "$period" =~ ^[0-9]+$ && "$period" -gt 0 ]]; then
  allowed=$(( (quota + period - 1) / period ))
  [ "$allowed" -lt 1 ] && allowed=1
  [ "$allowed" -lt "$cores" ] && cores=$allowed
fi
echo "$cores"
