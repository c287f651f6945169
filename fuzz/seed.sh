#!/usr/bin/env bash
# Builds the seed corpora in fuzz/corpus/{parse,check,scene} from the repository's own inputs:
# the example and stdlib shaders, the swatches, the shader sources inside compiler/tests/**/*.rs,
# and the example and test scenes. Run from anywhere; existing corpus entries are kept (libFuzzer
# adds to the same directories while it runs).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
corpus="$root/fuzz/corpus"
mkdir -p "$corpus/parse" "$corpus/check" "$corpus/scene"

# Each seed is named by its content's hash, as libFuzzer names its own entries.
add() { # add DIR FILE
    local sum
    sum="$(sha1sum "$2" | cut -d' ' -f1)"
    cp "$2" "$1/$sum"
}

shopt -s nullglob
for f in "$root"/examples/shaders/*.sl "$root"/compiler/stdlib/*.sl "$root"/docs/stdlib/swatches/*.sl; do
    add "$corpus/parse" "$f"
    add "$corpus/check" "$f"
done

# The shader sources in the compiler's tests: string literals that declare a shader or define
# a function, unescaped the way rustc reads them.
python3 - "$root/compiler/tests" "$corpus/parse" "$corpus/check" <<'PY'
import hashlib, pathlib, re, sys
tests, *dirs = sys.argv[1:]
# A raw string, or an ordinary one (escapes and line continuations undone).
literal = re.compile(r'r(#*)"(.*?)"\1|"((?:[^"\\]|\\.)*)"', re.S)
def unescape(body):
    body = re.sub(r'\\\n\s*', '', body)
    table = {'n': '\n', 't': '\t', '"': '"', '\\': '\\', "'": "'", '0': '\0', 'r': '\r'}
    return re.sub(r'\\(.)', lambda m: table.get(m.group(1), m.group(0)), body)
kinds = re.compile(r'\b(surface|light|displacement|volume|imager)\s+\w+\s*\(|^\s*#\s*(include|define)', re.M)
count = 0
for path in sorted(pathlib.Path(tests).rglob("*.rs")):
    for m in literal.finditer(path.read_text()):
        text = m.group(2) if m.group(2) is not None else unescape(m.group(3))
        if not kinds.search(text):
            continue
        data = text.encode()
        name = hashlib.sha1(data).hexdigest()
        for d in dirs:
            (pathlib.Path(d) / name).write_bytes(data)
        count += 1
print(f"seed.sh: {count} shaders from compiler/tests", file=sys.stderr)
PY

for f in "$root"/examples/scenes/*.toml "$root"/runtime/tests/scenes/*.toml; do
    add "$corpus/scene" "$f"
done

for t in parse check scene; do
    echo "seed.sh: $(ls "$corpus/$t" | wc -l) seeds in fuzz/corpus/$t" >&2
done
