"""The README's images are the product's: re-render them and compare with the
committed files, so that a shader or default change that alters what users
see is noticed (and the image is then regenerated on purpose).

    pvpython TestReadmeImages.py --demo PATH/MultiMaterialVolumeDemo
        --data Testing/Data/headsq.vti --image docs/demo.png --temp-dir DIR

docs/demo.png is what scripts/demo renders. llvmpipe renders it
deterministically (two runs: mean |difference| 0.0); the threshold of 0.3
catches a change of 0.75 grey levels on average (what switching the shading
normal to the gradient volume makes).
"""

import argparse
import os
import subprocess
import sys

from mmv_testing import read_png, mean_difference

THRESHOLD = 0.3  # mean |difference| per 8-bit channel


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--demo", required=True)
    p.add_argument("--data", required=True)
    p.add_argument("--image", required=True)
    p.add_argument("--temp-dir", required=True)
    args = p.parse_args()
    rendered = os.path.join(args.temp_dir, "readme_demo.png")
    if os.path.exists(rendered):
        os.remove(rendered)
    subprocess.run([args.demo, args.data, rendered], check=True)
    difference = mean_difference(read_png(rendered), read_png(args.image))
    print("demo against %s: mean |difference| %.3f (threshold %.2f)"
          % (args.image, difference, THRESHOLD))
    if not difference <= THRESHOLD:
        print("FAIL: the demo no longer renders %s; if the change is meant, run "
              "scripts/demo %s and look at the image" % (args.image, args.image))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
