#!/usr/bin/env bash
# Builds the fuzzing seed corpora in OUT_DIR/<target>/ from the hand-written seeds in this folder,
# small bags written by fuzz_seed_bags, and prefixes of the recorded files in DATA_DIR (never
# copied into the project). A missing DATA_DIR leaves only the hand-written and built seeds.
# usage: make_seeds.sh SEEDS_DIR DATA_DIR PROJECT_TEST_DATA OUT_DIR FUZZ_SEED_BAGS FUZZ_SEED_ROS2
set -euo pipefail
seeds=$1 data=$2 test_data=$3 out=$4 seed_bags=$5 seed_ros2=$6

rm -rf "$out"
mkdir -p "$out"/{map_yaml,map_image,carmen,ros_bag,tum,config,mcap,cdr,rosbag2_metadata,ros_map}
for target in map_yaml map_image carmen tum config ros_map; do
  cp "$seeds/$target"/* "$out/$target/"
done
"$seed_bags" "$out/ros_bag"
"$seed_ros2" "$out"
cp "$test_data"/*.yaml "$out/config/"

# A copy of FILE and its first N bytes for each N given (the cuts fall mid-record on purpose).
seed() {
  local target=$1 file=$2
  shift 2
  [ -f "$file" ] || return 0
  local base
  base=$(basename "$file")
  if [ $# -eq 0 ]; then
    cp "$file" "$out/$target/$base"
  fi
  for n in "$@"; do
    head -c "$n" "$file" >"$out/$target/$base.$n"
  done
}

# Binary PGM/PPM and PNG headers in a few bytes each (ASCII ones are hand-written seeds).
printf 'P5\n3 2\n255\n\x00\x80\xff\xcd\x01\x02' >"$out/map_image/gray8.pgm"
printf 'P5\n2 1\n65535\n\xff\xff\x00\x10' >"$out/map_image/gray16.pgm"
printf 'P6\n1 2\n255\n\xff\x00\x00\x00\xff\x00' >"$out/map_image/color6.ppm"

for yaml in "$data"/*/*.yaml; do seed map_yaml "$yaml"; done
seed map_image "$data/intel/intel.png"
seed map_image "$data/maps/basement_fixed.png"
seed map_image "$data/maps/basement_fixed.png" 2000 20000
seed map_image "$data/maps/turtlebot3_world.pgm" 100 30000
seed carmen "$data/intel/intel.clf" 4096 30000
seed carmen "$data/wean/robotdata1.clf" 4096 30000
seed ros_bag "$data/dis/dis-underground.bag" 65536 262144
seed tum "$data/intel/intel.gt.tum" 2000 20000
seed mcap "$data/ros2/mac_take2_zstd.mcap" 4096 65536
seed mcap "$data/ros2/mac_take2_lz4.mcap" 65536
seed mcap "$data/ros2/mac_take2_uncompressed.mcap" 30000
seed rosbag2_metadata "$data/ros2/mac_take2/metadata.yaml"
echo "fuzz seeds: $(find "$out" -type f | wc -l) files in $out"
