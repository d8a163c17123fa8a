# One device call (carry .gl): the merged shaders against those of fd13972, three probes, gpu-verify.
# Back as $OUT/final.tar.gz. SIZES and SMALL (gpu-verify --small) let the same script run on lavapipe.
sizes=${SIZES:-1920x1080,3840x2160}
if [ -d /usr/local/nvidia ]; then
  for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
  export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
fi
rm -rf /tmp/obscura-bundle /tmp/final && mkdir -p /tmp/final
tar -C /tmp -xzf .gl/obscura-bundle.tar.gz
O=/tmp/obscura-bundle/obscura
nvidia-smi --query-gpu=name,driver_version --format=csv > /tmp/final/smi.txt 2>&1
target=(--visibility-only --packed-history --keep-previous-depth --gtao-sampling planar-nearest --alternating-window
        --alternating-window-size 2 --packed-normals --packed-output)
run() {
  echo "final: [$SECONDS s] grid-ab" >&2
  scripts/gpu-ab --obscura $O --rounds 3 --json /tmp/final/grid-ab.json before=.gl/before after \
    -- --sizes $sizes --cases gtao-temporal-grid "${target[@]}" > /tmp/final/grid-ab.txt
  echo "final: [$SECONDS s] normals-ab (the frames of gtao-half and Alchemy)" >&2
  scripts/gpu-ab --obscura $O --rounds 3 --json /tmp/final/normals-ab.json before=.gl/before after \
    -- --sizes $sizes --cases alchemy,alchemy-fused,gtao,gtao-half --visibility-only --gtao-sampling planar-nearest \
    > /tmp/final/normals-ab.txt
  echo "final: [$SECONDS s] probes-ab" >&2
  scripts/gpu-ab --obscura $O --rounds 3 --json /tmp/final/probes-ab.json embedded \
    $(for d in .gl/probes/*/; do n=$(basename $d); echo "$n=$d"; done) \
    -- --sizes $sizes --cases gtao-half,gtao-temporal-grid "${target[@]}" > /tmp/final/probes-ab.txt
  scripts/gpu-ab --obscura $O --rounds 3 --json /tmp/final/probes-alchemy-ab.json embedded \
    alchemy-store-only=.gl/probes/alchemy-store-only -- --sizes $sizes --cases alchemy --visibility-only \
    > /tmp/final/probes-alchemy-ab.txt
  echo "final: [$SECONDS s] gpu-verify" >&2
  scripts/gpu-verify $O ${SMALL:+--small} > /tmp/final/verify.txt 2>&1
  echo "final: [$SECONDS s] done, gpu-verify exit $?" >&2
}
export -f run; export O sizes SMALL; export target_flags="${target[*]}"
timeout ${LIMIT:-250} bash -c "target=($target_flags); run" 2>&1 | tee /tmp/final/final.log
tar -C /tmp -czf ${OUT:-/tmp}/final.tar.gz final
