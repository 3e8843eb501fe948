// Binary packs from the server (sinews/studio/pack.py): "SNWP", a uint32 header
// length, a JSON header, then typed arrays at 8-byte aligned offsets.

const TYPES = { int16: Int16Array, float32: Float32Array, uint8: Uint8Array, int32: Int32Array };

/**
 * Decode a pack into its header and typed-array views (no copies).
 * @param {ArrayBuffer} buffer
 * @returns {{header: object, arrays: Object<string, {data: ArrayBufferView, shape: number[]}>}}
 */
export function decodePack(buffer) {
  const magic = new TextDecoder().decode(new Uint8Array(buffer, 0, 4));
  if (magic !== "SNWP") throw new Error("the server sent something that is not a motion pack");
  const length = new DataView(buffer).getUint32(4, true);
  const header = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, 8, length)));
  const base = 8 + length;
  const arrays = {};
  for (const [name, spec] of Object.entries(header.arrays)) {
    const Type = TYPES[spec.dtype];
    const count = spec.shape.reduce((a, b) => a * b, 1);
    arrays[name] = { data: new Type(buffer, base + spec.offset, count), shape: spec.shape };
  }
  return { header, arrays };
}
