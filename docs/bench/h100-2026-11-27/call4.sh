for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
tar -C /tmp -xzf .gl/obscura-bundle.tar.gz
mkdir -p /tmp/waiting
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > /tmp/waiting/waiting-smi.txt 2>&1
pack() { tar -C /tmp -czf "$OUT/.waiting.tar.gz" waiting waiting.log && mv "$OUT/.waiting.tar.gz" "$OUT/waiting.tar.gz"; }
timeout 540 scripts/gpu-waiting --obscura /tmp/obscura-bundle/obscura --candidates .gl/candidates \
  --parts candidates-ab,candidates-grid-ab,pipelines,verify /tmp/waiting \
  -- --sizes 1920x1080,3840x2160 >/tmp/waiting.log 2>&1 &
job=$!
ticks=0
while kill -0 $job 2>/dev/null; do
  sleep 1
  ticks=$((ticks + 1))
  if [ $((ticks % 20)) = 0 ]; then pack; fi
done
wait $job; echo "gpu-waiting exit status $?" >>/tmp/waiting.log
pack
tail -3 /tmp/waiting.log; cat /tmp/waiting/targets.txt /tmp/waiting/candidates.txt 2>/dev/null | tail -c 10000
