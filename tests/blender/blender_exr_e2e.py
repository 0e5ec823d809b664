#!/usr/bin/python3
"""End to end: Blender (Debian `blender`, headless) opens every kind of EXR
skybake writes and gives the values OpenImageIO reads from it.

    tests/blender/blender_exr_e2e.py [SKYBAKE]     (default: build/skybake)

Bakes a small scene whose outputs cover every EXR shape and encoding
skybake writes (docs/formats.md "EXR" "Shapes"): a 2D image in float32 and
in half, zip and uncompressed, a volume atlas, and a 2D array (one part per
layer, channels named "layer<i>.<channel>"). Blender 3.4 aborts on a
multi-part file whose parts repeat plain channel names, so the array is the
case this guards. Each file is loaded with `blender -b --python-expr`: a
single image through `Image.pixels` (bottom row first), a multi-layer file,
whose pixels Blender keeps from Python, through its compositor, which
renders the first and the last layer to float EXRs read back here. Every
channel Blender shows (at most three) must equal OpenImageIO's reading of
the same part within 1e-6 relative (both decode the same float32 or half
values). Blender missing fails the test: scripts/install-deps.sh installs it.
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

BLENDER_SCRIPT = """
import bpy, sys
args = sys.argv[sys.argv.index('--') + 1:]
path, width, height, out = args[0], int(args[1]), int(args[2]), args[3]
layers = args[4:]
im = bpy.data.images.load(path)
px = list(im.pixels)
print('TYPE', im.type)
if px:
    w, h, c = im.size[0], im.size[1], im.channels
    print('SIZE', w, h, c)
    print('PIXELS', ' '.join(repr(v) for v in px))
else:
    sc = bpy.context.scene
    sc.use_nodes = True
    tree = sc.node_tree
    for n in list(tree.nodes):
        tree.nodes.remove(n)
    node = tree.nodes.new('CompositorNodeImage')
    node.image = im
    print('OUTPUTS', ' '.join(o.name for o in node.outputs if o.enabled))
    comp = tree.nodes.new('CompositorNodeComposite')
    sc.render.resolution_x, sc.render.resolution_y = width, height
    sc.render.resolution_percentage = 100
    sc.render.image_settings.file_format = 'OPEN_EXR'
    sc.render.image_settings.color_depth = '32'
    sc.view_settings.view_transform = 'Standard'
    sc.render.engine = 'BLENDER_WORKBENCH'
    for layer in layers:
        tree.links.new(node.outputs[layer], comp.inputs[0])
        sc.render.filepath = out + '.' + layer + '.exr'
        bpy.ops.render.render(write_still=True)
        print('RENDERED', layer)
"""


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    return p.returncode, p.stdout + p.stderr


def oiio_parts(path):
    """Every part of `path` as OpenImageIO reads it: (name, width, height,
    channel names, rows of texels top first, channels interleaved)."""
    rc, text = run(["oiiotool", "--info", "-v", path])
    if rc != 0:
        fail("OpenImageIO cannot read %s: %s" % (path, text))
    count = int(re.search(r"oiio:subimages: (\d+)", text).group(1)) if "oiio:subimages" in text else 1
    parts = []
    for i in range(count):
        tmp = path + ".part%d.exr" % i
        rc, text = run(["oiiotool", path, "--subimage", str(i), "-d", "float", "-o", tmp])
        if rc != 0:
            fail("oiiotool cannot extract part %d of %s: %s" % (i, path, text))
        rc, text = run(["oiiotool", "--info", "-v", "--dumpdata", tmp])
        os.remove(tmp)
        m = re.search(r":\s+(\d+) x\s+(\d+), (\d+) channel", text)
        names = re.search(r"channel list: ([^\n]*)", text).group(1).split(", ")
        values = [[float(v) for v in line.split()]
                  for line in re.findall(r"Pixel \(\d+, \d+\): ([^\n]*)", text)]
        name = re.search(r'oiio:subimagename: "([^"]*)"', text)
        parts.append((name.group(1) if name else "", int(m.group(1)), int(m.group(2)), names, values))
    return parts


def expect_close(what, got, want):
    if abs(got - want) > 1e-6 * max(1.0, abs(want)):
        fail("%s: Blender gives %r, OpenImageIO %r" % (what, got, want))


def check_file(path, scratch):
    parts = oiio_parts(path)
    _, width, height, names, texels = parts[0]
    layers = [p[0] for p in parts] if len(parts) > 1 else []
    chosen = sorted({layers[0], layers[-1]}) if layers else []
    out = os.path.join(scratch, os.path.basename(path))
    rc, text = run(["blender", "-b", "--factory-startup", "--python-expr", BLENDER_SCRIPT, "--",
                    path, str(width), str(height), out] + chosen)
    if rc != 0 or "Traceback" in text or "crash" in text.lower():
        fail("Blender could not open %s (exit %s):\n%s" % (path, rc, text[-2000:]))
    nc = min(3, len(names))
    if not layers:
        size = re.search(r"^SIZE (\d+) (\d+) (\d+)", text, re.M)
        pixels = re.search(r"^PIXELS (.*)$", text, re.M)
        if not size or not pixels:
            fail("Blender gave no pixels for %s:\n%s" % (path, text[-2000:]))
        w, h, c = (int(v) for v in size.groups())
        if (w, h) != (width, height):
            fail("%s: Blender reads %dx%d, OpenImageIO %dx%d" % (path, w, h, width, height))
        px = [float(v) for v in pixels.group(1).split()]
        for y in range(height):
            for x in range(width):
                for ch in range(nc):
                    # Blender's rows run from the bottom of the image.
                    expect_close("%s (%d, %d) %s" % (path, x, y, names[ch]),
                                 px[((height - 1 - y) * width + x) * c + ch],
                                 texels[y * width + x][ch])
        return "image %dx%d, %d channels" % (width, height, len(names))
    shown = re.search(r"^OUTPUTS (.*)$", text, re.M)
    if not shown or shown.group(1).split() != layers:
        fail("%s: Blender shows layers %s, the file has parts %s" %
             (path, shown.group(1) if shown else "none", layers))
    for layer in chosen:
        rendered = out + "." + layer + ".exr"
        if not os.path.exists(rendered):
            fail("%s: Blender rendered no %s:\n%s" % (path, layer, text[-2000:]))
        _, w, h, _, got = oiio_parts(rendered)[0]
        want = parts[layers.index(layer)][4]
        if (w, h) != (width, height):
            fail("%s %s: Blender renders %dx%d" % (path, layer, w, h))
        for i, (g, t) in enumerate(zip(got, want)):
            for ch in range(nc):
                expect_close("%s %s texel %d channel %d" % (path, layer, i, ch), g[ch], t[ch])
    return "%d layers (%s checked)" % (len(layers), ", ".join(chosen))


def main():
    skybake = sys.argv[1] if len(sys.argv) > 1 else os.path.join(SOURCE, "build", "skybake")
    if not shutil.which("blender"):
        fail("blender not found (Debian package blender; scripts/install-deps.sh)")
    scratch = tempfile.mkdtemp(prefix="skybake_blender_")
    scene = {
        "name": "blender",
        "planet": {"radius_km": 6360, "ground_albedo": [0.3, 0.3, 0.3]},
        "atmosphere": os.path.join(SOURCE, "presets/atmospheres/earth.json"),
        "clouds": os.path.join(SOURCE, "presets/clouds/storm.json"),
        "outputs": [
            {"product": "transmittance", "size": [32, 16], "formats": ["exr"]},
            {"product": "skyview", "size": [24, 12], "formats": ["exr"], "precision": "half"},
            {"product": "aerial_perspective", "size": [8, 8, 8], "formats": ["exr"]},
            {"product": "weather", "size": [16, 16], "formats": ["exr"], "precision": "half"},
            {"product": "noise_detail", "size": [8, 8, 8], "formats": ["exr"],
             "worley": [{"period": 2, "octaves": 1}, {"period": 2, "octaves": 1},
                        {"period": 4, "octaves": 1}]},
        ],
    }
    preset = os.path.join(scratch, "blender.json")
    with open(preset, "w") as f:
        json.dump(scene, f)
    rc, text = run([skybake, "bake", preset, "--out", os.path.join(scratch, "out"), "--quiet"])
    if rc not in (0,):
        fail("bake failed: " + text)
    files = sorted(os.path.join(scratch, "out", "blender", f)
                   for f in os.listdir(os.path.join(scratch, "out", "blender")) if f.endswith(".exr"))
    if len(files) != len(scene["outputs"]):
        fail("expected %d EXR files, got %s" % (len(scene["outputs"]), files))
    for path in files:
        print("ok  %s: %s" % (os.path.basename(path), check_file(path, scratch)), flush=True)
    shutil.rmtree(scratch)
    print("PASS: Blender opens every EXR kind skybake writes")


if __name__ == "__main__":
    main()
