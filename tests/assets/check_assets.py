#!/usr/bin/env python3
"""Checks of the real-asset suite (samples/assets/, suite 'assets').

    check_assets.py reproducible LIGHT_ASSETS_PY ASSETS_DIR
        regenerating the wrappers from lights.json (<Name>.lit.gltf, and <Name>.punctual.gltf for
        the assets that list punctual lights) gives the committed files, byte for byte; a
        punctual wrapper of an asset that lists none is stale
    check_assets.py licences ASSETS_DIR
        every asset of lights.json has a LICENSE.md naming a permissive SPDX licence, a source
        and its changes, a row in README.md, every file its glTF references, and stays small
    check_assets.py load SCENE_LOAD_EACH FILE.gltf
        the project's loader (tests/scene/scene_load_each) loads FILE: exit 0 on
        RTPBR_GLTF_SUCCESS, 1 otherwise
"""
import filecmp
import json
import os
import subprocess
import sys
import tempfile

# Permissive licences the suite accepts (SPDX ids); a non-commercial or share-alike-only
# licence (CC-BY-NC-*, CC-BY-SA-*) keeps an asset out.
ALLOWED_LICENCES = ("CC0-1.0", "CC-BY-4.0", "Apache-2.0", "MIT")
MAX_ASSET_BYTES = 5 * 1024 * 1024  # "each under a few MB" (issue 28); SheenCloth, 3.9 MB, is the largest
MAX_SUITE_BYTES = 15 * 1024 * 1024


def spec(assets):
    with open(os.path.join(assets, "lights.json"), encoding="utf-8") as f:
        return json.load(f)["assets"]


def names(assets):
    return sorted(spec(assets))


def wrappers(assets, name):
    """The wrapper files lights.json makes for one asset."""
    return [name + ".lit.gltf"] + ([name + ".punctual.gltf"] if "punctual" in spec(assets)[name] else [])


def reproducible(tool, assets):
    bad = []
    count = 0
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run([sys.executable, tool, "--spec", os.path.join(assets, "lights.json"), "--assets", assets,
                        "--out", tmp], check=True, stderr=subprocess.DEVNULL)
        for n in names(assets):
            for w in wrappers(assets, n):
                count += 1
                a = os.path.join(tmp, n, w)
                b = os.path.join(assets, n, w)
                if not os.path.exists(b) or not filecmp.cmp(a, b, shallow=False):
                    bad.append(b)
            stale = os.path.join(assets, n, n + ".punctual.gltf")
            if os.path.exists(stale) and n + ".punctual.gltf" not in wrappers(assets, n):
                bad.append(stale + " (lights.json lists no punctual light for it)")
    if bad:
        print("stale or missing wrappers (run tools/assets/light_assets.py):", " ".join(bad))
        return 1
    print("%d wrappers (lit and punctual) match lights.json" % count)
    return 0


def referenced_files(gltf):
    with open(gltf, encoding="utf-8") as f:
        doc = json.load(f)
    uris = [b.get("uri") for b in doc.get("buffers", [])] + [i.get("uri") for i in doc.get("images", [])]
    return [u for u in uris if u and not u.startswith("data:")]


def licences(assets):
    problems = []
    with open(os.path.join(assets, "README.md"), encoding="utf-8") as f:
        index = f.read()
    total = 0
    for n in names(assets):
        folder = os.path.join(assets, n)
        lic = os.path.join(folder, "LICENSE.md")
        if not os.path.isfile(lic):
            problems.append("%s: no LICENSE.md" % n)
            continue
        with open(lic, encoding="utf-8") as f:
            text = f.read()
        spdx = [s for s in ALLOWED_LICENCES if "`%s`" % s in text]
        if len(spdx) != 1:
            problems.append("%s: LICENSE.md names no single accepted SPDX id (%s)" % (n, ", ".join(ALLOWED_LICENCES)))
        for field in ("**Source**", "**Author / copyright**", "**Changes**"):
            if field not in text:
                problems.append("%s: LICENSE.md has no %s line" % (n, field))
        if "| %s |" % n not in index:
            problems.append("%s: no row in samples/assets/README.md" % n)
        for gltf in [n + ".gltf"] + wrappers(assets, n):
            path = os.path.join(folder, gltf)
            if not os.path.isfile(path):
                problems.append("%s: %s missing" % (n, gltf))
                continue
            for uri in referenced_files(path):
                if not os.path.isfile(os.path.join(folder, uri)):
                    problems.append("%s: %s references %s, which is missing" % (n, gltf, uri))
        size = sum(os.path.getsize(os.path.join(folder, f)) for f in os.listdir(folder))
        total += size
        if size > MAX_ASSET_BYTES:
            problems.append("%s: %d bytes, over %d" % (n, size, MAX_ASSET_BYTES))
    if total > MAX_SUITE_BYTES:
        problems.append("the suite holds %d bytes, over %d" % (total, MAX_SUITE_BYTES))
    for p in problems:
        print(p)
    if not problems:
        print("%d assets: licences, sources, index rows and files in place (%.1f MB)" % (len(names(assets)),
                                                                                       total / 1048576.0))
    return 1 if problems else 0


def load(loader, gltf):
    out = subprocess.run([loader, gltf], capture_output=True, text=True)
    print(out.stdout.strip())
    if out.returncode != 0:
        print(out.stderr.strip())
        return 1
    fields = out.stdout.split()
    return 0 if len(fields) >= 2 and fields[1] == "RTPBR_GLTF_SUCCESS" else 1


def main(argv):
    if len(argv) >= 3 and argv[0] == "reproducible":
        return reproducible(argv[1], argv[2])
    if len(argv) >= 2 and argv[0] == "licences":
        return licences(argv[1])
    if len(argv) >= 3 and argv[0] == "load":
        return load(argv[1], argv[2])
    print(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
