// XML for the module's 3MF and AMF readers: parsed here by @rgrove/parse-xml
// (npm) and flattened into the tables web/src/pugixml_on_javascript/pugixml.hpp
// reads as a pugixml document. Kept as pugixml's parse_default keeps them:
// elements, text that is not all white space (space, tab, CR, LF), CDATA.

// Node fields (pugixml.hpp's detail::Tree::Field) and node types (pugi::xml_node_type).
const FIELDS = 8;
const [TYPE, NAME, VALUE, FIRST_CHILD, NEXT_SIBLING, FIRST_ATTRIBUTE, ATTRIBUTE_COUNT, OFFSET] = [0, 1, 2, 3, 4, 5, 6, 7];
const DOCUMENT = 1, ELEMENT = 2, PCDATA = 3, CDATA = 4;
// pugi::xml_encoding
const UTF8 = 1, UTF16_LE = 2, UTF16_BE = 3, LATIN1 = 4;

// A growing Int32Array.
class Ints {
  constructor() { this.a = new Int32Array(1 << 12); this.n = 0; }
  reserve(k) {
    if (this.n + k <= this.a.length) return;
    const b = new Int32Array(Math.max(2 * this.a.length, this.n + k));
    b.set(this.a.subarray(0, this.n));
    this.a = b;
  }
  view() { return this.a.subarray(0, this.n); }
}

// Latin-1 bytes as text, byte for code point (TextDecoder's 'latin1' is
// windows-1252, which reads 0x80-0x9F as other characters).
function latin1(b) {
  const parts = [];
  for (let i = 0; i < b.length; i += 8192) parts.push(String.fromCharCode.apply(null, b.subarray(i, i + 8192)));
  return parts.join('');
}

// The text of the bytes, as pugixml's encoding_auto reads them: a byte-order
// mark or a UTF-16 '<' names the encoding; a declaration that says
// ISO-8859-1 or latin1 gives Latin-1; otherwise UTF-8.
function decode(b) {
  if (b[0] === 0xef && b[1] === 0xbb && b[2] === 0xbf) return { encoding: UTF8, skip: 3, text: new TextDecoder('utf-8').decode(b) };
  if ((b[0] === 0xff && b[1] === 0xfe && (b[2] !== 0 || b[3] !== 0)) || (b[0] === 0x3c && b[1] === 0 && (b[2] !== 0 || b[3] !== 0)))
    return { encoding: UTF16_LE, skip: 0, text: new TextDecoder('utf-16le').decode(b) };
  if ((b[0] === 0xfe && b[1] === 0xff) || (b[0] === 0 && b[1] === 0x3c && b[2] === 0))
    return { encoding: UTF16_BE, skip: 0, text: new TextDecoder('utf-16be').decode(b) };
  if ((b[0] === 0 && b[1] === 0) || (b[2] === 0 && b[3] === 0 && b[0] !== 0))
    throw new Error('UTF-32 is not read by polyvol\'s WebAssembly build');
  if (/^<\?xml[^>]*encoding\s*=\s*["'](iso-8859-1|latin1)["']/i.test(latin1(b.subarray(0, 200))))
    return { encoding: LATIN1, skip: 0, text: latin1(b) };
  return { encoding: UTF8, skip: 0, text: new TextDecoder('utf-8').decode(b) };
}

// The UTF-8 length of text[from, to) (UTF-16 units).
function utf8Length(text, from, to) {
  let n = 0;
  for (let i = from; i < to; ++i) {
    const c = text.charCodeAt(i);
    n += c < 0x80 ? 1 : c < 0x800 ? 2 : c >= 0xd800 && c < 0xdc00 ? 4 : c >= 0xdc00 && c < 0xe000 ? 0 : 3;
  }
  return n;
}

const ALL_SPACE = /^[ \t\r\n]*$/;

// {ok: true, encoding, nodes, attributes, strings} or {ok: false, message, offset}.
export function xmlTables(parseXml, bytes) {
  let decoded;
  try {
    decoded = decode(bytes);
  } catch (e) {
    return { ok: false, message: e.message, offset: 0 };
  }
  const { text, encoding, skip } = decoded;
  let doc;
  try {
    // Comments kept (and skipped below) so that text on either side of one
    // stays two nodes, as pugixml has it (parse-xml would join them).
    doc = parseXml(text, { includeOffsets: true, preserveCdata: true, preserveComments: true, ignoreUndefinedEntities: true });
  } catch (e) {
    // parse-xml counts its error position in code points.
    let units = 0;
    for (let k = 0; k < (e.pos ?? 0) && units < text.length; ++k) units += text.codePointAt(units) > 0xffff ? 2 : 1;
    const offset = encoding === UTF8 ? skip + utf8Length(text, 0, units) : units;
    return { ok: false, message: String(e.message).split('\n')[0], offset };
  }

  const strings = [''];
  const names = new Map();
  const name = (s) => {
    let k = names.get(s);
    if (k === undefined) { k = strings.length; strings.push(s); names.set(s, k); }
    return k;
  };
  const nodes = new Ints();
  const attributes = new Ints();
  const ascii = encoding === UTF8 && text.length + skip === bytes.length;
  let unit = 0, byte = skip;  // the byte offset of text[unit], for documents that are not ASCII
  const add = (type, n, v, start) => {
    nodes.reserve(FIELDS);
    const i = nodes.n / FIELDS;
    const a = nodes.a;
    let offset = start + skip;  // pugixml counts a byte-order mark
    if (!ascii && encoding === UTF8 && start >= unit) { byte += utf8Length(text, unit, start); unit = start; offset = byte; }
    else if (!ascii && encoding === UTF8) offset = skip + utf8Length(text, 0, start);
    a[nodes.n + TYPE] = type; a[nodes.n + NAME] = n; a[nodes.n + VALUE] = v;
    a[nodes.n + FIRST_CHILD] = -1; a[nodes.n + NEXT_SIBLING] = -1;
    a[nodes.n + FIRST_ATTRIBUTE] = attributes.n / 2; a[nodes.n + ATTRIBUTE_COUNT] = 0; a[nodes.n + OFFSET] = offset;
    nodes.n += FIELDS;
    return i;
  };
  add(DOCUMENT, 0, 0, 0);
  // Pre-order, so that offsets grow and siblings are linked as they come.
  const frames = [{ element: doc, index: 0, next: 0, last: -1 }];
  while (frames.length) {
    const f = frames[frames.length - 1];
    if (f.next === f.element.children.length) { frames.pop(); continue; }
    const c = f.element.children[f.next++];
    let i;
    if (c.type === 'element') {
      i = add(ELEMENT, name(c.name), 0, c.start + 1);  // pugixml: the offset of the name, after '<'
      const keys = Object.keys(c.attributes);
      attributes.reserve(2 * keys.length);
      for (const k of keys) {
        attributes.a[attributes.n++] = name(k);
        attributes.a[attributes.n++] = strings.push(c.attributes[k]) - 1;
      }
      nodes.a[i * FIELDS + ATTRIBUTE_COUNT] = keys.length;
    } else if (c.type === 'cdata') {
      i = add(CDATA, 0, strings.push(c.text) - 1, c.start);
    } else if (c.type === 'text' && !ALL_SPACE.test(c.text)) {
      i = add(PCDATA, 0, strings.push(c.text) - 1, c.start);
    } else {
      continue;
    }
    if (f.last < 0) nodes.a[f.index * FIELDS + FIRST_CHILD] = i;
    else nodes.a[f.last * FIELDS + NEXT_SIBLING] = i;
    f.last = i;
    if (c.type === 'element') frames.push({ element: c, index: i, next: 0, last: -1 });
  }
  const blob = new TextEncoder().encode(strings.join('\0') + '\0');
  return { ok: true, encoding, nodes: nodes.view(), attributes: attributes.view(), strings: blob, stringCount: strings.length };
}
