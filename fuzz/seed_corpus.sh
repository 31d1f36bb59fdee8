#!/usr/bin/env bash
# Fills fuzz/corpus/<target>/ with seed inputs (the corpora are not committed):
#   xml_scene   the scene files assets/scenes/*.xml and assets/reference/*.xml,
#               and mesh.xml, a <mesh> placing the smallest glTF sample
#   gltf_model  the glTF samples (self-contained .gltf with data: URIs) in
#               $GLTF_SAMPLES (default /work/shared/gltf) and assets/models if
#               it exists, plus each converted to a .glb (BIN chunk + images
#               in buffer views)
#   glb_model   the same .glb files in glb_model's input form: JSON, a 0 byte,
#               then the BIN chunk's bytes
# Usage: fuzz/seed_corpus.sh   (from anywhere; needs python3)
set -euo pipefail
fuzz="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$fuzz")"
samples="${GLTF_SAMPLES:-/work/shared/gltf}"
mkdir -p "$fuzz/corpus/xml_scene" "$fuzz/corpus/gltf_model" "$fuzz/corpus/glb_model"

for f in "$root"/assets/scenes/*.xml "$root"/assets/reference/*.xml; do
  cp "$f" "$fuzz/corpus/xml_scene/$(basename "$(dirname "$f")")-$(basename "$f")"
done

models=()
for dir in "$samples" "$root/assets/models"; do
  [ -d "$dir" ] || continue
  while IFS= read -r -d '' f; do models+=("$f"); done \
    < <(find "$dir" -maxdepth 2 -type f \( -name '*.gltf' -o -name '*.glb' \) -print0)
done
[ ${#models[@]} -gt 0 ] || { echo "no glTF samples found in $samples" >&2; exit 1; }

# A scene that places the smallest model, so the reader's <mesh> path is seeded too.
smallest="$(ls -S "${models[@]}" | tail -n 1)"
printf '<scene>\n  <mesh src="%s" translate="0 1 0" scale="2" material="metal"/>\n</scene>\n' \
  "$smallest" > "$fuzz/corpus/xml_scene/mesh.xml"

python3 - "$fuzz/corpus" "${models[@]}" <<'PY'
import base64, json, os, struct, sys

corpus, models = sys.argv[1], sys.argv[2:]

def data_uri(uri):
    """The bytes of a base64 data: URI, or None for anything else."""
    if uri and uri.startswith("data:") and ";base64," in uri:
        return base64.b64decode(uri.split(";base64,", 1)[1])
    return None

def pad(data, fill):
    return data + fill * (-len(data) % 4)

def to_bin(doc):
    """Moves buffer 0 and every data: URI image into one BIN chunk.
    Returns None when buffer 0 is not a data: URI (external file)."""
    buffers = doc.get("buffers", [])
    if not buffers or data_uri(buffers[0].get("uri")) is None:
        return None
    bin = bytearray(pad(data_uri(buffers[0].pop("uri")), b"\0"))
    for image in doc.get("images", []):
        data = data_uri(image.get("uri"))
        if data is None:
            continue
        mime = image.pop("uri")[5:].split(";", 1)[0] or "image/png"
        doc.setdefault("bufferViews", []).append(
            {"buffer": 0, "byteOffset": len(bin), "byteLength": len(data)})
        image.update(bufferView=len(doc["bufferViews"]) - 1, mimeType=mime)
        bin += pad(data, b"\0")
    buffers[0]["byteLength"] = len(bin)
    return bytes(bin)

def glb(json_bytes, bin):
    body = b""
    for kind, data, fill in ((b"JSON", json_bytes, b" "), (b"BIN\0", bin, b"\0")):
        data = pad(data, fill)
        body += struct.pack("<I", len(data)) + kind + data
    return b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body

for path in models:
    name = os.path.splitext(os.path.basename(path))[0]
    raw = open(path, "rb").read()
    open(os.path.join(corpus, "gltf_model", os.path.basename(path)), "wb").write(raw)
    if path.endswith(".glb"):
        continue
    doc = json.loads(raw)
    bin = to_bin(doc)
    if bin is None:
        print(f"{path}: buffer 0 is not a data: URI; no .glb made", file=sys.stderr)
        continue
    text = json.dumps(doc, separators=(",", ":")).encode()
    open(os.path.join(corpus, "gltf_model", name + ".glb"), "wb").write(glb(text, bin))
    open(os.path.join(corpus, "glb_model", name), "wb").write(text + b"\0" + bin)
PY
for t in xml_scene gltf_model glb_model; do
  echo "$t: $(ls "$fuzz/corpus/$t" | wc -l) seeds"
done
