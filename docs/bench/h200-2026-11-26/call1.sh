# One device call (carry .gl): everything that waits for a GPU, back as $OUT/waiting.tar.gz.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
tar -C /tmp -xzf .gl/obscura-bundle.tar.gz
nvidia-smi --query-gpu=name,driver_version,clocks.sm --format=csv > /tmp/waiting-smi.txt 2>&1
# Bounded, so that the archive below is written inside the call's limit (give the call about 560 s).
timeout 480 scripts/gpu-waiting --obscura /tmp/obscura-bundle/obscura --candidates .gl/candidates --probes .gl/probes --parts fused-ab,normals-ab,candidates-ab,candidates-grid-ab,probes-ab,pipelines,verify /tmp/waiting -- --sizes 1920x1080,3840x2160 2>&1 | tee /tmp/waiting.log
cp /tmp/waiting-smi.txt /tmp/waiting/
tar -C /tmp -czf $OUT/waiting.tar.gz waiting waiting.log
