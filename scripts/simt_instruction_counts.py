#!/usr/bin/env python3
"""Instruction counts of the CUDA kernels under backends/cuda/, by class and
program section, for the SIMT cost model (backends/simt_backend.h).

Compiles every kernel with nvcc to PTX (and, where a disassembler is
available, to SASS through a cubin), finds in each kernel the loop that
fetches one node per pass, and counts the instructions of every section:

  prologue   blocks outside that loop from which it can be reached
  loop       the loop's blocks: one loop pass
  epilogue   the other blocks reachable from the entry
  beam_leaf  ray kernels only, for the docs: prologue + epilogue of the
             kernel with a beam leaf minus those of the kernel without

Each block counts once (a static count): a warp whose lanes take both
sides of a branch issues both, which is what a loop pass costs a divergent
warp. Out-of-line subroutines (the SASS slow paths of division and square
root) count as their CALL only. Docs: docs/simt_instruction_counts.md.

  --write   regenerate backends/simt_instruction_table.json
  --check   recompile and compare with the committed table (exit 0 equal,
            1 different, 77 skipped: no nvcc, or another nvcc version)
  (none)    print the counts

The node-fetch loop is the innermost loop holding an instruction that the
compiler attributes (-lineinfo) to a source line marked RC_NODE_FETCH (the
node's address or its load: a compiler may load the fields where they are
used).
"""
import argparse
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
KERNEL_DIR = os.path.join(REPO, "backends", "cuda")
TABLE = os.path.join(REPO, "backends", "simt_instruction_table.json")
SKIP = 77

# The artifact's Vulkan-Sim configuration models a Turing GPU: compute
# capability 7.5 (-gpgpu_compute_capability_major 7, _minor 5,
# -gpgpu_ptx_force_max_capability 75). nvcc 13.0 still compiles for sm_75.
ARCH = "sm_75"
# -fmad=false: the host build contracts nothing into FMA, so the double
# kernels round as the host kernels do. -lineinfo: the node-fetch marker
# (it changes no instruction; checked by the test).
NVCC_FLAGS = ["-arch=" + ARCH, "-fmad=false", "-lineinfo", "-std=c++17"]

CLASSES = ["fp32", "fp64", "int", "fp32_div", "fp64_div", "int_div", "sfu", "load", "store", "branch", "other"]

SOURCES = ["ray_cast_kernels.cu", "sact_kernel.cu", "sphere_kernel.cu", "ball_query_kernels.cu"]

# Shipped step program (robocore/programs) -> entry point prefix; the ray
# programs also have kernels with the max-log beam leaf of beam_leaf.asm
# (_beam) and with the host's exact beam density (_beam_exact).
PROGRAMS = {
    "grid_march.asm": "rc_march",
    "dda_step.asm": "rc_dda",
    "rm_step.asm": "rc_rm",
    "sact_obb_aabb.asm": "rc_sact",
    "sphere_aabb.asm": "rc_sphere",
    "ball_query_psphere.asm": "rc_ball_query_psphere",
    "ball_query_pray.asm": "rc_ball_query_pray",
}
RAY_PROGRAMS = ("grid_march.asm", "dda_step.asm", "rm_step.asm")
LEAVES = {"with_beam_leaf": ("_beam", "beam_leaf"), "with_exact_beam_leaf": ("_beam_exact", "exact_beam_leaf")}
PRECISIONS = ["fp32", "fp64"]


class Failure(Exception):
    pass


def run(cmd, **kw):
    r = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if r.returncode != 0:
        raise Failure("command failed: %s\n%s%s" % (" ".join(cmd), r.stdout, r.stderr))
    return r


# ---------------------------------------------------------------- classes

def ptx_class(opcode):
    """Class of a PTX instruction, as the artifact's GPGPU-Sim times it
    (ptx_instruction::set_opcode_and_latency): add/sub/min/max/mul/mad/fma
    by type (f32, f64, integer), div by type, the SFU opcodes, loads,
    stores, branches; everything else is an ALU op of latency 1."""
    parts = opcode.split(".")
    base, mods = parts[0], parts[1:]
    if base in ("ld", "ldu"):
        return "load"
    if base in ("st", "red", "atom"):
        return "store"
    if base in ("bra", "brx", "ret", "exit", "call", "trap"):
        return "branch"
    if base in ("rcp", "sqrt", "rsqrt", "sin", "cos", "ex2", "lg2", "tanh"):
        return "sfu"
    if base in ("div", "rem"):
        if "f64" in mods:
            return "fp64_div"
        if "f32" in mods:
            return "fp32_div"
        return "int_div"
    if base in ("add", "sub", "addc", "subc", "min", "max", "mul", "mad", "madc", "fma", "mul24", "mad24"):
        if "f64" in mods:
            return "fp64"
        if "f32" in mods or "f16" in mods or "f16x2" in mods:
            return "fp32"
        return "int"
    return "other"


SASS_FP32 = {"FADD", "FMUL", "FFMA", "FMNMX", "FSETP", "FSET", "FSEL", "FCHK", "FSWZADD", "FRND", "FADD32I",
             "FMUL32I", "FFMA32I"}
SASS_FP64 = {"DADD", "DMUL", "DFMA", "DSETP", "DSET", "DMNMX"}
SASS_CONVERSIONS = {"F2F", "F2I", "I2F", "FRND"}
SASS_INT = {"IADD3", "IADD", "IMAD", "IMNMX", "ISETP", "ISET", "LEA", "LOP3", "LOP", "SHF", "SHL", "SHR", "IABS",
            "POPC", "FLO", "BREV", "PRMT", "SEL", "IMUL", "ICMP", "VIADD", "BMSK", "SGXT", "IDP", "ISCADD", "XMAD",
            "IADD32I", "IMUL32I", "LOP32I", "IMAD32I"}
SASS_LOAD = {"LDG", "LD", "LDL", "LDS", "LDC", "LDSM"}
SASS_STORE = {"STG", "ST", "STL", "STS", "RED", "ATOM", "ATOMG", "ATOMS"}
SASS_BRANCH = {"BRA", "BRX", "JMP", "JMX", "CALL", "RET", "EXIT", "BSSY", "BSYNC", "WARPSYNC", "BREAK", "KILL",
               "BPT"}


def sass_class(opcode):
    """Class of a SASS instruction by its mnemonic: the FP32 and FP64 pipes'
    opcodes, conversions by operand width (an F64 conversion runs on the
    FP64 unit), the integer pipe, MUFU, loads, stores, control flow; the
    rest (moves, S2R, predicate logic, uniform-datapath ops) is other."""
    parts = opcode.split(".")
    base, mods = parts[0], parts[1:]
    if base in SASS_FP64:
        return "fp64"
    if base in SASS_CONVERSIONS:
        return "fp64" if "F64" in mods else ("fp32" if base == "FRND" else "other")
    if base in SASS_FP32:
        return "fp32"
    if base in SASS_INT:
        return "int"
    if base == "MUFU":
        return "sfu"
    if base in SASS_LOAD:
        return "load"
    if base in SASS_STORE:
        return "store"
    if base in SASS_BRANCH:
        return "branch"
    return "other"


# ---------------------------------------------------------------- parsing

class Instruction:
    __slots__ = ("opcode", "predicated", "target", "file", "line", "text")

    def __init__(self, opcode, predicated, target, file, line, text):
        self.opcode, self.predicated, self.target = opcode, predicated, target
        self.file, self.line, self.text = file, line, text


def parse_ptx(text):
    """{entry name: [label string | Instruction]} of a PTX module."""
    files = {m.group(1): m.group(2) for m in re.finditer(r'^\s*\.file\s+(\d+)\s+"([^"]+)"', text, re.M)}
    entries = {}
    for m in re.finditer(r"^\.visible \.entry (\w+)\(", text, re.M):
        start = text.index("{", m.end())
        depth, i = 0, start
        while True:
            if text[i] == "{":
                depth += 1
            elif text[i] == "}":
                depth -= 1
                if depth == 0:
                    break
            i += 1
        body = text[start + 1:i]
        items, file, line = [], None, None
        for raw in body.split("\n"):
            s = raw.strip()
            if not s or s.startswith("//"):
                continue
            loc = re.match(r"\.loc\s+(\d+)\s+(\d+)\s+\d+", s)
            if loc:
                file, line = files.get(loc.group(1)), int(loc.group(2))
                continue
            if s.startswith(".") or s in ("{", "}"):
                continue
            lab = re.match(r"^(\$?[\w$]+):$", s)
            if lab:
                items.append(lab.group(1))
                continue
            ins = re.match(r"^(@!?%\w+\s+)?([a-z][\w.]*)\s*(.*?);?$", s)
            if not ins:
                raise Failure("unparsed PTX line in %s: %s" % (m.group(1), s))
            opcode, rest = ins.group(2), ins.group(3)
            target = None
            if opcode.split(".")[0] == "bra":
                target = rest.strip().rstrip(";").strip()
            items.append(Instruction(opcode, bool(ins.group(1)), target, file, line, s))
        entries[m.group(1)] = items
    return entries


def parse_sass(text):
    """{function name: [label string | Instruction]} of nvdisasm -g output."""
    functions, current, file, line = {}, None, None, None
    for raw in text.split("\n"):
        s = raw.strip()
        head = re.match(r"//-+ \.text\.(\S+)\s+-+", s)
        if head:
            current = functions.setdefault(head.group(1), [])
            file = line = None
            continue
        if current is None or not s:
            continue
        loc = re.match(r'//## File "([^"]+)", line (\d+)', s)
        if loc:
            file, line = loc.group(1), int(loc.group(2))
            continue
        lab = re.match(r"^(\.L_x_\d+):$", s)
        if lab:
            current.append(lab.group(1))
            continue
        ins = re.match(r"^/\*[0-9a-f]+\*/\s+(@!?U?P\w+\s+)?([A-Z][\w.]*)\s*(.*?)\s*;", s)
        if not ins:
            continue
        opcode, rest = ins.group(2), ins.group(3)
        target = None
        t = re.search(r"`\((\.L_x_\d+)\)", rest)
        if t and opcode.split(".")[0] in ("BRA", "BRX", "JMP"):
            target = t.group(1)
        current.append(Instruction(opcode, bool(ins.group(1)), target, file, line, s))
    return functions


# ---------------------------------------------------------------- control flow

def basic_blocks(items, isa):
    """Splits a function into basic blocks: (blocks, successors), a block
    being a list of Instructions, successors a list of block indices."""
    is_jump = (lambda o: o.split(".")[0] == "bra") if isa == "ptx" else (
        lambda o: o.split(".")[0] in ("BRA", "BRX", "JMP"))
    is_end = (lambda o: o.split(".")[0] in ("ret", "exit", "trap")) if isa == "ptx" else (
        lambda o: o.split(".")[0] in ("EXIT", "RET", "KILL"))
    blocks, labels, current = [], {}, []

    def close():
        nonlocal current
        if current:
            blocks.append(current)
            current = []

    for it in items:
        if isinstance(it, str):
            close()
            labels[it] = len(blocks)
            continue
        current.append(it)
        if is_jump(it.opcode) or is_end(it.opcode):
            close()
    close()
    succ = []
    for b, block in enumerate(blocks):
        last = block[-1]
        s = []
        if is_jump(last.opcode):
            if last.target not in labels:
                raise Failure("branch to an unknown label: " + last.text)
            s.append(labels[last.target])
            if last.predicated and b + 1 < len(blocks):
                s.append(b + 1)
        elif is_end(last.opcode):
            if last.predicated and b + 1 < len(blocks):
                s.append(b + 1)
        elif b + 1 < len(blocks):
            s.append(b + 1)
        succ.append(s)
    return blocks, succ


def reachable_from(start, succ):
    seen, todo = {start}, [start]
    while todo:
        for n in succ[todo.pop()]:
            if n not in seen:
                seen.add(n)
                todo.append(n)
    return seen


def dominators(succ, nodes):
    pred = {n: [p for p in nodes if n in succ[p]] for n in nodes}
    dom = {n: set(nodes) for n in nodes}
    dom[0] = {0}
    changed = True
    while changed:
        changed = False
        for n in sorted(nodes):
            if n == 0:
                continue
            new = set.intersection(*(dom[p] for p in pred[n])) if pred[n] else set()
            new = new | {n}
            if new != dom[n]:
                dom[n], changed = new, True
    return dom, pred


def natural_loops(succ, nodes):
    """{header: set of blocks} from every back edge u -> h (h dominates u)."""
    dom, pred = dominators(succ, nodes)
    loops = {}
    for u in nodes:
        for h in succ[u]:
            if h in dom[u]:
                body = loops.setdefault(h, {h})
                todo = [u]
                while todo:
                    n = todo.pop()
                    if n not in body:
                        body.add(n)
                        todo.extend(p for p in pred[n] if p in nodes)
    return loops


def sections(items, isa, marker_lines, name):
    """Per-section class counts of one function."""
    blocks, succ = basic_blocks(items, isa)
    nodes = reachable_from(0, succ)
    loops = natural_loops(succ, nodes)
    classify = ptx_class if isa == "ptx" else sass_class

    def fetches(b):
        return any(i.file and (os.path.basename(i.file), i.line) in marker_lines for i in blocks[b])

    candidates = [(len(body), h, body) for h, body in loops.items() if any(fetches(b) for b in body)]
    if not candidates:
        raise Failure("%s (%s): no loop holds an instruction of an RC_NODE_FETCH line" % (name, isa))
    _, header, loop = min(candidates, key=lambda c: (c[0], c[1]))
    to_header = {n for n in nodes if header in reachable_from(n, succ)} - loop
    out = {s: dict.fromkeys(CLASSES, 0) for s in ("prologue", "loop", "epilogue")}
    for b in nodes:
        section = "loop" if b in loop else ("prologue" if b in to_header else "epilogue")
        for ins in blocks[b]:
            out[section][classify(ins.opcode)] += 1
    return out


# ---------------------------------------------------------------- toolchain

def find_tool(name):
    """RC_<NAME> if set (empty: none), else PATH, else /usr/local/cuda/bin."""
    variable = "RC_" + name.upper()
    candidates = [os.environ[variable]] if variable in os.environ else [shutil.which(name),
                                                                        "/usr/local/cuda/bin/" + name]
    for path in candidates:
        if path and os.path.isfile(path) and os.access(path, os.X_OK):
            return path
    return None


def tool_version(path):
    out = run([path, "--version"]).stdout.strip().split("\n")
    return [l for l in out if "release" in l or l.startswith("Build")][0].strip()


def marker_lines():
    marks = set()
    for name in sorted(os.listdir(KERNEL_DIR)):
        if name.endswith((".cu", ".cuh")):
            with open(os.path.join(KERNEL_DIR, name)) as f:
                for n, line in enumerate(f, 1):
                    if "RC_NODE_FETCH" in line and not line.lstrip().startswith("//"):
                        marks.add((name, n))
    if not marks:
        raise Failure("no RC_NODE_FETCH marker under " + KERNEL_DIR)
    return marks


def nvcc_command(nvcc, source, kind, output):
    rel = os.path.relpath(os.path.join(KERNEL_DIR, source), REPO)
    return [nvcc] + NVCC_FLAGS + ["-I.", "-" + kind, rel, "-o", output]


def downgrade_elf_abi(cubin):
    """A copy of a cubin whose ELF header says ABI version 7 with the
    pre-CUDA-12.8 e_flags (sm | 0x100 | 0x400 | sm << 16), so an older
    nvdisasm reads it. The instructions are untouched."""
    data = bytearray(open(cubin, "rb").read())
    if data[8] != 8:
        return cubin
    flags = struct.unpack_from("<I", data, 0x30)[0]
    sm = (flags >> 8) & 0xFF
    data[8] = 7
    struct.pack_into("<I", data, 0x30, sm | 0x100 | 0x400 | (sm << 16))
    patched = cubin + ".abi7"
    with open(patched, "wb") as f:
        f.write(data)
    return patched


def disassemble(nvdisasm, cubin):
    r = subprocess.run([nvdisasm, "-g", "-c", cubin], capture_output=True, text=True)
    if r.returncode == 0:
        return r.stdout, False
    if "architecture information" not in r.stderr:
        raise Failure("nvdisasm failed on %s: %s" % (cubin, r.stderr))
    return run([nvdisasm, "-g", "-c", downgrade_elf_abi(cubin)]).stdout, True


def compile_all(nvcc, nvdisasm, workdir):
    marks = marker_lines()
    functions = {"ptx": {}, "sass": {}}
    registers, commands, abi_rewritten = {}, [], False
    for source in SOURCES:
        stem = os.path.splitext(source)[0]
        ptx = os.path.join(workdir, stem + ".ptx")
        cmd = nvcc_command(nvcc, source, "ptx", ptx)
        run(cmd, cwd=REPO)
        commands.append(cmd)
        functions["ptx"].update(parse_ptx(open(ptx).read()))
        cubin = os.path.join(workdir, stem + ".cubin")
        cmd = nvcc_command(nvcc, source, "cubin", cubin) + ["-Xptxas", "-v"]
        r = run(cmd, cwd=REPO)
        commands.append(cmd)
        for m in re.finditer(r"Compiling entry function '(\w+)'.*?Used (\d+) registers", r.stdout + r.stderr, re.S):
            registers[m.group(1)] = int(m.group(2))
        if nvdisasm:
            text, rewritten = disassemble(nvdisasm, cubin)
            abi_rewritten = abi_rewritten or rewritten
            functions["sass"].update(parse_sass(text))
    return functions, registers, commands, marks, abi_rewritten


def subtract(a, b):
    return {c: a[c] - b[c] for c in CLASSES}


def kernel_entry(functions, registers, marks, isas, name):
    entry = {"kernel": name, "registers": registers[name]}
    for isa in isas:
        entry[isa] = sections(functions[isa][name], isa, marks, name)
    return entry


def once(s):
    return {c: s["prologue"][c] + s["epilogue"][c] for c in CLASSES}


def build_table(functions, registers, marks, isas):
    programs = {}
    for program, prefix in PROGRAMS.items():
        entry = {}
        for precision in PRECISIONS:
            per = kernel_entry(functions, registers, marks, isas, "%s_%s" % (prefix, precision))
            kernels = [per]
            if program in RAY_PROGRAMS:
                for key, (suffix, added) in LEAVES.items():
                    leaf = kernel_entry(functions, registers, marks, isas, "%s%s_%s" % (prefix, suffix, precision))
                    per[key] = leaf
                    kernels.append(leaf)
                    # For the docs: what the leaf adds to the once-per-query
                    # sections (the model prices the with-leaf kernel as compiled).
                    for isa in isas:
                        per[isa][added] = subtract(once(leaf[isa]), once(per[isa]))
            if precision == "fp32":
                for kernel in kernels:
                    for isa in isas:
                        for section, counts in kernel[isa].items():
                            if counts["fp64"] or counts["fp64_div"]:
                                raise Failure("%s (%s) %s: FP64 instructions in a float kernel" % (
                                    kernel["kernel"], isa, section))
            entry[precision] = per
        programs[program] = entry
    return programs


def command_string(cmd):
    return " ".join(os.path.basename(c) if i == 0 else c for i, c in enumerate(cmd))


def generate(nvcc, nvdisasm):
    with tempfile.TemporaryDirectory() as workdir:
        functions, registers, commands, marks, rewritten = compile_all(nvcc, nvdisasm, workdir)
        isas = ["ptx"] + (["sass"] if nvdisasm else [])
        table = {
            "generated_by": "python3 scripts/simt_instruction_counts.py --write",
            "nvcc": tool_version(nvcc),
            "arch": ARCH,
            "compile_commands": [command_string(c).replace(workdir + os.sep, "") for c in commands],
            "nvdisasm": (tool_version(nvdisasm) + (" (cubin ELF header rewritten to ABI 7 to be read)"
                                                  if rewritten else "")) if nvdisasm else None,
            "classes": CLASSES,
            "sections": "prologue/epilogue: once per query; loop: one pass (one node fetch); "
                        "beam_leaf, exact_beam_leaf: what the leaf adds, once per ray (docs only)",
            "programs": build_table(functions, registers, marks, isas),
        }
    return table


def flatten(node, prefix=""):
    """{"path/to/section": counts} of a table entry's count dictionaries."""
    out = {}
    for key, value in node.items():
        path = prefix + "/" + key if prefix else key
        if isinstance(value, dict):
            out.update(flatten(value, path))
        else:
            out[path] = value
    return out


def compare(committed, fresh, with_sass):
    """Differences between two tables' programs, one line each."""
    old, new = flatten(committed["programs"]), flatten(fresh["programs"])
    if not with_sass:
        old = {k: v for k, v in old.items() if "/sass/" not in k}
    return ["%s: committed %s, compiled %s" % (k, old.get(k), new.get(k))
            for k in sorted(set(old) | set(new)) if old.get(k) != new.get(k)]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--write", action="store_true", help="regenerate " + os.path.relpath(TABLE, REPO))
    group.add_argument("--check", action="store_true", help="compare a fresh compile with the committed table")
    args = parser.parse_args()
    nvcc = find_tool("nvcc")
    if not nvcc:
        print("SKIPPED: no nvcc (set RC_NVCC, put nvcc on PATH, or install the CUDA toolkit at /usr/local/cuda); "
              "the committed table %s is used as it is" % os.path.relpath(TABLE, REPO))
        return SKIP
    nvdisasm = find_tool("nvdisasm")
    try:
        if args.check:
            committed = json.load(open(TABLE))
            version = tool_version(nvcc)
            if version != committed["nvcc"]:
                print("SKIPPED: nvcc here is '%s', the table was made by '%s'; regenerate with --write to "
                      "adopt this compiler" % (version, committed["nvcc"]))
                return SKIP
            fresh = generate(nvcc, nvdisasm)
            diffs = compare(committed, fresh, bool(nvdisasm))
            if not nvdisasm:
                print("note: no nvdisasm; SASS counts not rechecked (PTX only)")
            if diffs:
                print("the committed table differs from a fresh compile "
                      "(regenerate: python3 scripts/simt_instruction_counts.py --write):")
                print("\n".join(diffs))
                return 1
            print("OK: %d programs x %d precisions match the committed table (%s)" % (
                len(committed["programs"]), len(PRECISIONS), "PTX and SASS" if nvdisasm else "PTX"))
            return 0
        table = generate(nvcc, nvdisasm)
        if args.write:
            with open(TABLE, "w") as f:
                json.dump(table, f, indent=1, sort_keys=False)
                f.write("\n")
            print("wrote " + os.path.relpath(TABLE, REPO))
        else:
            json.dump(table, sys.stdout, indent=1)
            print()
        return 0
    except Failure as e:
        print("error: %s" % e, file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
