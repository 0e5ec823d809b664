#!/usr/bin/python3
"""Compiles every runtime include with glslangValidator (Debian glslang-tools).

Usage: compile_shaders.py RUNTIME_DIR

Every file of RUNTIME_DIR/glsl/*.glsl and RUNTIME_DIR/hlsl/*.hlsl, found when
the test runs (so files added later are compiled too), is compiled on its
own, preceded by the files its `// requires: a, b` lines name (recursively,
dependencies first, each once; docs/runtime.md "Using the includes"):

- GLSL: `#version 450 core`, the includes and a compute `main` that does
  nothing, validated as desktop GLSL 4.50 (glslangValidator's default
  target). No include may use `#extension`: the runtime is plain 4.50.
- HLSL: the includes and a `[numthreads(1, 1, 1)]` compute `main`, through
  glslangValidator's HLSL front end (-D, which needs -V).

glslang type-checks every function it parses, called or not, so the empty
main is enough. Exits 1 naming each file that fails with the compiler's
output, and when glslangValidator is missing or a folder holds no file.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile


def requires(path):
    names = []
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.startswith("// requires:"):
                names += [n for n in re.split(r"[,\s]+", line[len("// requires:"):]) if n]
    return names


def include_order(folder, name, seen, active, order):
    if name in seen:
        return
    if name in active:
        raise RuntimeError(f"{folder}/{name}: includes require each other in a cycle")
    path = os.path.join(folder, name)
    if not os.path.isfile(path):
        raise RuntimeError(f"{path}: required but missing")
    active.add(name)
    for dep in requires(path):
        include_order(folder, dep, seen, active, order)
    active.discard(name)
    seen.add(name)
    order.append(name)


def source_of(folder, name):
    order = []
    include_order(folder, name, set(), set(), order)
    text = ""
    for n in order:
        with open(os.path.join(folder, n), encoding="utf-8") as f:
            text += f.read().rstrip("\n") + "\n"
    return text, order


def compile_one(tool, folder, name, language, scratch):
    source, order = source_of(folder, name)
    if language == "glsl":
        if re.search(r"^\s*#\s*extension", source, re.M):
            return f"uses #extension (the runtime is plain GLSL 4.50)"
        wrapper = "#version 450 core\n" + source + "layout(local_size_x = 1) in;\nvoid main() {}\n"
        path = os.path.join(scratch, name + ".comp")
        command = [tool, path]
    else:
        wrapper = source + "[numthreads(1, 1, 1)]\nvoid main() {}\n"
        path = os.path.join(scratch, name)
        command = [tool, "-D", "-V", "-S", "comp", "-e", "main", "-o", os.devnull, path]
    with open(path, "w", encoding="utf-8") as f:
        f.write(wrapper)
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        return f"(with {', '.join(order)}) {' '.join(command)}\n{result.stdout}{result.stderr}"
    return None


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    runtime = sys.argv[1]
    tool = shutil.which("glslangValidator")
    if not tool:
        print("compile_shaders: glslangValidator not found (install glslang-tools, "
              "scripts/install-deps.sh)")
        return 1
    failures = []
    compiled = 0
    with tempfile.TemporaryDirectory() as scratch:
        for language, ext in (("glsl", ".glsl"), ("hlsl", ".hlsl")):
            folder = os.path.join(runtime, language)
            names = sorted(n for n in os.listdir(folder) if n.endswith(ext)) \
                if os.path.isdir(folder) else []
            if not names:
                failures.append(f"{folder}: no *{ext} file")
            for name in names:
                try:
                    problem = compile_one(tool, folder, name, language, scratch)
                except RuntimeError as e:
                    problem = str(e)
                compiled += 1
                status = "ok" if problem is None else "FAILED"
                print(f"{language}/{name}: {status}")
                if problem is not None:
                    failures.append(f"{language}/{name}: {problem}")
    for f in failures:
        print(f, file=sys.stderr)
    print(f"{compiled} files, {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
