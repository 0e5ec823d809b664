#!/usr/bin/python3
"""Which common tool reads which skybake file: the measurement behind the
table of docs/formats.md "Which tools read which file".

Usage: scripts/measure-reader-compat.py SKYBAKE OUT_DIR

Bakes one small scene per DDS variant (format x header x shape) into OUT_DIR
with the given skybake, each output also written as EXR, then opens every DDS
and EXR file with each tool that is installed: OpenImageIO (oiiotool), Pillow
(Debian python3-pil through /usr/bin/python3), ImageMagick (/usr/bin/convert)
and Blender (headless). A DDS counts as read when the tool gives the file's
width and height and its first channel of the first slice matches the
file's own texels, decoded here from the specifications (Microsoft Learn
"DDS_HEADER", Khronos Data Format Specification "S3TC", "RGTC"), within two
8-bit steps (tools decode block formats to 8 bits with their own rounding)
or 1e-3 relative for float formats; an EXR when that channel matches what
OpenImageIO reads. Prints Markdown tables. Each tool gets 60 s per file;
"hangs" means it took longer.
"""
import json
import os
import re
import shutil
import struct
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(HERE)
TIMEOUT = 60

NOISE_SHAPE = {"perlin": {"period": 4, "octaves": 2}, "perlin_worley": {"period": 4, "octaves": 2},
               "worley": [{"period": 4, "octaves": 2}, {"period": 4, "octaves": 2},
                          {"period": 8, "octaves": 1}]}
NOISE_DETAIL = {"worley": [{"period": 2, "octaves": 2}, {"period": 2, "octaves": 2},
                           {"period": 4, "octaves": 1}], "pack": "single_channel"}

# (label, product, options); every case with both headers where a legacy one exists.
CASES = [
    ("RGBA8 2D", "weather", {"size": [32, 32], "dds_format": "R8G8B8A8_UNORM"}),
    ("R8G8 2D", "cloud_types", {"size": [32], "type_width": 8, "dds_format": "R8G8_UNORM"}),
    ("BC1 2D", "weather", {"size": [32, 32], "dds_format": "BC1_UNORM"}),
    ("BC3 2D", "height_gradients", {"size": [32], "dds_format": "BC3_UNORM"}),
    ("BC5 2D", "cloud_types", {"size": [32], "type_width": 8, "dds_format": "BC5_UNORM"}),
    ("R8 volume", "noise_detail", dict(NOISE_DETAIL, size=[16, 16, 16], dds_format="R8_UNORM")),
    ("BC4 volume", "noise_detail", dict(NOISE_DETAIL, size=[16, 16, 16], dds_format="BC4_UNORM")),
    ("RGBA8 volume", "noise_shape", dict(NOISE_SHAPE, size=[16, 16, 16], dds_format="R8G8B8A8_UNORM")),
    ("BC3 volume", "noise_shape", dict(NOISE_SHAPE, size=[16, 16, 16], dds_format="BC3_UNORM")),
    ("float32 2D", "transmittance", {"size": [32, 16], "dds_format": "R32G32B32A32_FLOAT"}),
    ("half 2D", "transmittance", {"size": [32, 16], "dds_format": "R16G16B16A16_FLOAT"}),
    ("R11G11B10 2D", "transmittance", {"size": [32, 16], "dds_format": "R11G11B10_FLOAT"}),
    ("float32 2D array", "skyview", {"size": [32, 16], "dds_format": "R32G32B32A32_FLOAT"}),
]
NO_LEGACY = {"R11G11B10 2D", "float32 2D array"}


def run(cmd, **kw):
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=TIMEOUT, **kw)
        return p.returncode, p.stdout + p.stderr
    except subprocess.TimeoutExpired:
        return "hang", ""


def bake(skybake, out):
    presets = os.path.join(out, "presets")
    os.makedirs(presets, exist_ok=True)
    scenes = []
    for label, product, options in CASES:
        for header in ["legacy", "dx10"]:
            if header == "legacy" and label in NO_LEGACY:
                continue
            name = re.sub(r"[^a-z0-9]+", "_", label.lower()) + "_" + header
            output = dict(options, product=product, name="t", formats=["dds", "exr"],
                          dds_header=header)
            scene = {"name": name, "atmosphere": os.path.join(SOURCE, "presets/atmospheres/earth.json"),
                     "clouds": os.path.join(SOURCE, "presets/clouds/storm.json"),
                     "planet": {"radius_km": 6360, "ground_albedo": [0.3, 0.3, 0.3]},
                     "outputs": [output]}
            with open(os.path.join(presets, name + ".json"), "w") as f:
                json.dump(scene, f)
            scenes.append((label, header, os.path.join(out, name, "t")))
    rc, text = run([skybake, "bake", presets, "--out", out, "--quiet"])
    if rc != 0:
        sys.exit("bake failed: " + text)
    return scenes


# Each reader returns (width, height, first channel of slice 0, top row first) or a failure word.
def read_oiio(path):
    rc, text = run(["oiiotool", "--info", "--dumpdata", path])
    if rc != 0:
        return "hangs" if rc == "hang" else "error"
    m = re.search(r":\s+(\d+) x\s+(\d+)", text)
    values = []
    for line in re.finditer(r"Pixel \(\d+, \d+(?:, \d+)?\): ([^\n]*)", text):
        fields = line.group(1)  # "bytes (floats)" for integer data, "floats" for float data
        if "(" in fields:
            fields = fields[fields.index("(") + 1:]
        values.append(float(fields.replace(",", " ").replace(")", " ").split()[0]))
    return int(m.group(1)), int(m.group(2)), values


PIL_SCRIPT = """
import sys
from PIL import Image
im = Image.open(sys.argv[1])
im.load()
print(im.size[0], im.size[1], im.mode)
band = im.getchannel(0)
scale = 255.0 if im.mode in ('L', 'LA', 'RGB', 'RGBA', 'P') else 1.0
print(' '.join(repr(v / scale) for v in band.getdata()))
"""


def read_pillow(path):
    rc, text = run(["/usr/bin/python3", "-c", PIL_SCRIPT, path])
    if rc != 0:
        return "hangs" if rc == "hang" else "error"
    lines = text.splitlines()
    w, h, _ = lines[0].split()
    return int(w), int(h), [float(v) for v in lines[1].split()]


def read_imagemagick(path):
    if not os.path.exists("/usr/bin/convert"):
        return None
    rc, text = run(["/usr/bin/identify", "-format", "%w %h\n", path + "[0]"])
    if rc != 0:
        return "hangs" if rc == "hang" else "error"
    w, h = (int(v) for v in text.split()[:2])
    try:
        raw = subprocess.run(["/usr/bin/convert", path + "[0]", "-depth", "16", "rgba:-"],
                             capture_output=True, timeout=TIMEOUT).stdout
    except subprocess.TimeoutExpired:
        return "hangs"
    values = [int.from_bytes(raw[i:i + 2], "big") / 65535.0 for i in range(0, len(raw), 8)]
    return w, h, values


# Blender gives Python no pixels of a multi-layer EXR (one layer per part):
# its compositor renders the first layer to a float EXR instead, which
# OpenImageIO reads back. `size` is the file's, since Blender reports 0 x 0.
BLENDER_SCRIPT = """
import bpy, sys
path, width, height, out = sys.argv[-4], int(sys.argv[-3]), int(sys.argv[-2]), sys.argv[-1]
im = bpy.data.images.load(path)
px = list(im.pixels)
if px:
    w, h = im.size
    c = im.channels
    rows = [px[(y * w) * c:(y + 1) * w * c:c] for y in range(h)]
    print('SIZE', w, h)
    print('VALUES', ' '.join(repr(v) for row in reversed(rows) for v in row))
else:
    sc = bpy.context.scene
    sc.use_nodes = True
    tree = sc.node_tree
    for n in list(tree.nodes):
        tree.nodes.remove(n)
    node = tree.nodes.new('CompositorNodeImage')
    node.image = im
    comp = tree.nodes.new('CompositorNodeComposite')
    tree.links.new([o for o in node.outputs if o.enabled][0], comp.inputs[0])
    sc.render.resolution_x, sc.render.resolution_y = width, height
    sc.render.resolution_percentage = 100
    sc.render.image_settings.file_format = 'OPEN_EXR'
    sc.render.image_settings.color_depth = '32'
    sc.view_settings.view_transform = 'Standard'
    sc.render.engine = 'BLENDER_WORKBENCH'
    sc.render.filepath = out
    bpy.ops.render.render(write_still=True)
    print('LAYER', im.type)
"""


def read_blender(path, size=(0, 0)):
    if not shutil.which("blender"):
        return None
    out = path + ".blender.exr"
    rc, text = run(["blender", "-b", "--factory-startup", "--python-expr", BLENDER_SCRIPT, "--",
                    path, str(size[0]), str(size[1]), out])
    if rc == "hang":
        return "hangs"
    if rc != 0 or "Segmentation" in text or "crash.txt" in text:
        return "crash"
    if re.search(r"^LAYER MULTILAYER", text, re.M) and os.path.exists(out):
        got = read_oiio(out)
        os.remove(out)
        return got
    size = re.search(r"^SIZE (\d+) (\d+)", text, re.M)
    values = re.search(r"^VALUES (.*)$", text, re.M)
    if not size or not values:
        return "error"
    return int(size.group(1)), int(size.group(2)), [float(v) for v in values.group(1).split()]


# ---- the reference: the first channel of level 0, every depth slice, from the file's bytes

def bc1_red(block, four_colours):
    c0, c1 = struct.unpack_from("<HH", block)
    r0, r1 = (c0 >> 11) / 31.0, (c1 >> 11) / 31.0
    if four_colours or c0 > c1:
        palette = [r0, r1, (2 * r0 + r1) / 3, (r0 + 2 * r1) / 3]
    else:
        palette = [r0, r1, (r0 + r1) / 2, 0.0]
    bits = struct.unpack_from("<I", block, 4)[0]
    return [palette[(bits >> (2 * i)) & 3] for i in range(16)]


def bc4_red(block):
    r0, r1 = block[0] / 255.0, block[1] / 255.0
    if block[0] > block[1]:
        palette = [r0, r1] + [((7 - i) * r0 + i * r1) / 7 for i in range(1, 7)]
    else:
        palette = [r0, r1] + [((5 - i) * r0 + i * r1) / 5 for i in range(1, 5)] + [0.0, 1.0]
    bits = int.from_bytes(block[2:8], "little")
    return [palette[(bits >> (3 * i)) & 7] for i in range(16)]


def decode_red(path, fmt):
    data = open(path, "rb").read()
    height, width = struct.unpack_from("<II", data, 12)
    depth = max(1, struct.unpack_from("<I", data, 24)[0])
    offset = 148 if data[84:88] == b"DX10" else 128
    slices = [decode_slice(data[offset:], width, height, fmt, z) for z in range(depth)]
    return width, height, [v for s in slices for v in s]


def decode_slice(data, width, height, fmt, z):
    """The first channel of depth slice z of level 0."""
    if fmt in ("BC1", "BC3", "BC4", "BC5"):
        size = 8 if fmt in ("BC1", "BC4") else 16
        bw = (width + 3) // 4
        p = data[z * bw * ((height + 3) // 4) * size:]
        out = [0.0] * (width * height)
        for by in range((height + 3) // 4):
            for bx in range(bw):
                block = p[(by * bw + bx) * size:(by * bw + bx + 1) * size]
                texels = {"BC1": lambda b: bc1_red(b, False), "BC3": lambda b: bc1_red(b[8:], True),
                          "BC4": bc4_red, "BC5": bc4_red}[fmt](block)
                for i, v in enumerate(texels):
                    x, y = bx * 4 + i % 4, by * 4 + i // 4
                    if x < width and y < height:
                        out[y * width + x] = v
        return out
    n = width * height
    bytes_per_texel = {"R32G32B32A32_FLOAT": 16, "R16G16B16A16_FLOAT": 8, "R11G11B10_FLOAT": 4,
                       "R8G8B8A8_UNORM": 4, "R8G8_UNORM": 2, "R8_UNORM": 1}[fmt]
    p = data[z * n * bytes_per_texel:]
    if fmt == "R32G32B32A32_FLOAT":
        return [struct.unpack_from("<f", p, 16 * i)[0] for i in range(n)]
    if fmt == "R16G16B16A16_FLOAT":
        return [struct.unpack_from("<e", p, 8 * i)[0] for i in range(n)]
    if fmt == "R11G11B10_FLOAT":
        def f11(v):
            e, m = v >> 6, v & 63
            return (m / 64.0) * 2.0 ** -14 if e == 0 else (1 + m / 64.0) * 2.0 ** (e - 15)
        return [f11(struct.unpack_from("<I", p, 4 * i)[0] & 0x7FF) for i in range(n)]
    return [p[bytes_per_texel * i] / 255.0 for i in range(n)]


def verdict(got, ref, volume):
    """"yes", "slice 0 only" (a volume read as its first slice, or with
    only that slice right), or what went wrong."""
    if got is None:
        return "not installed"
    if isinstance(got, str):
        return got
    w, h, values = got
    rw, rh, rvalues = ref
    if w * h == 0:
        return "error"
    if (w, h) != (rw, rh) or len(values) < w * h:
        return "wrong size %dx%d" % (w, h)

    def close(vs, ref_values):
        return all(abs(a - b) <= max(2.0 / 255.0, 1e-3 * abs(b)) for a, b in zip(vs, ref_values))

    n = w * h
    if not close(values[:n], rvalues[:n]):
        flipped = [v for y in reversed(range(h)) for v in values[y * w:(y + 1) * w]]
        return "upside down" if close(flipped, rvalues[:n]) else "wrong values"
    if volume and not (len(values) == len(rvalues) and close(values, rvalues)):
        return "slice 0 only"
    return "yes"


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    skybake, out = sys.argv[1], sys.argv[2]
    scenes = bake(skybake, out)
    tools = [("OIIO", read_oiio), ("Pillow", read_pillow), ("ImageMagick", read_imagemagick),
             ("Blender", read_blender)]
    print("| file | header | " + " | ".join(t for t, _ in tools) + " |")
    print("|---|---|" + "---|" * len(tools))
    for label, header, stem in scenes:
        volume = "volume" in label
        fmt = next(o["dds_format"] for l, _, o in CASES if l == label).replace("_UNORM", "")
        fmt = {"R8G8B8A8": "R8G8B8A8_UNORM", "R8G8": "R8G8_UNORM", "R8": "R8_UNORM"}.get(fmt, fmt)
        ref = decode_red(stem + ".dds", fmt)
        cells = [verdict(read(stem + ".dds"), ref, volume) for _, read in tools]
        print("| %s | %s | %s |" % (label, header, " | ".join(cells)), flush=True)
    print()
    print("| EXR | " + " | ".join(t for t, _ in tools) + " |")
    print("|---|" + "---|" * len(tools))
    for label, header, stem in scenes:
        if header != "dx10":
            continue
        ref = read_oiio(stem + ".exr")
        cells = [verdict(read(stem + ".exr", ref[:2]) if read is read_blender else read(stem + ".exr"),
                         ref, False) for _, read in tools]
        print("| %s | %s |" % (label, " | ".join(cells)), flush=True)


if __name__ == "__main__":
    main()
