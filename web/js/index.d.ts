// polyvol: the command line's figures for a mesh file, computed in WebAssembly.

/** A request's options: the command line's flags, camelCase or snake_case. */
export interface Options {
  /** cone (default), prism, pyramid or vtnb. */
  method?: 'cone' | 'prism' | 'pyramid' | 'vtnb';
  /** exact (correctly rounded, the default) or fast (with an error bound). */
  accuracy?: 'exact' | 'correctly-rounded' | 'fast' | 'bounded';
  /** A number (mass per output unit³) or with a unit: "1.24g/cm3", "2700kg/m3". */
  density?: string | number;
  /** The mass unit for a density with a unit: kg (default), g or lb. */
  massUnit?: 'kg' | 'g' | 'lb';
  /** The coordinates' unit (3MF, AMF and glTF state theirs: units overrides it, with a note, unless unitsWhereUnstated). */
  units?: 'mm' | 'cm' | 'm' | 'in' | 'ft' | 'micron' | 'um';
  /** units only for a file that states none. */
  unitsWhereUnstated?: boolean;
  /** The figures' unit (default: the coordinates', or metres with a density with a unit). */
  to?: 'mm' | 'cm' | 'm' | 'in' | 'ft' | 'micron' | 'um';
  /** Every coordinate times this first. */
  scale?: string | number;
  /** Measure surfaces with unbalanced edges anyway. */
  allowOpen?: boolean;
  /** Look for a surface crossing itself at any size. */
  solid?: boolean;
  /** Wind the faces consistently and outward first. */
  orient?: boolean;
  /** Keep an inside-out surface's signed figures. */
  keepSigned?: boolean;
  /** Merge points closer than this first. */
  weldTolerance?: number;
  /** volume only: the table's figures, a binary STL streamed whatever its size (its shells not checked for overlap). */
  stream?: boolean;
  /** volume only: the volume, its guarantee and the closedness check, nothing else (`volume --volume-only --json`); with stream, one pass over a binary STL. */
  volumeOnly?: boolean;
  /** Called while each file is measured: each stage as it begins (fraction 0), a streamed STL's passes by whole percents, ('measuring', 1) at its end. */
  onProgress?: (p: Progress) => void;
}

/** One file's figures: the object `polyvol measure --json` prints (see docs/cli.md), one per mesh. */
export type Report = Record<string, unknown> & { file: string; exit_code: number; error?: string; warning?: string };

export interface Progress {
  /** The file as the results name it ("parts.zip:a.stl" for a member). */
  file: string;
  stage: 'reading' | 'checking' | 'measuring';
  /** Of the stage: 0 as it begins; 0..1 through a streamed binary STL's records. */
  fraction: number;
}

export interface Answer {
  /** One object per mesh of the file, keys as the command line's JSON. */
  results: Report[];
  /** The command line's exit code: 0 ok, 1 usage, 2 unreadable, 3 not valid for the request, 4 out of memory or an internal error. */
  exitCode: number;
  /** What the command line prints on stderr (errors and warnings). */
  messages: string[];
  /** The command line's JSON, byte for byte. */
  json: string;
  /** measure only: what `polyvol measure --csv` prints for the same request (RFC 4180, CRLF, a header row). */
  csv?: string;
  /** Each reader's note in the results ("stl-multiple-solids(2)") in words ("2 solids in one file, measured together"). */
  noteWords?: Record<string, string>;
}

/** A ∩ B, A ∪ B, A − B and B − A: the object `polyvol overlap --json` prints. */
export interface OverlapAnswer {
  result: Record<string, unknown> | null;
  exitCode: number;
  messages: string[];
  json: string;
}

/** overlap's options: the solid policy and the units. */
export type OverlapOptions = Pick<Options, 'units' | 'unitsWhereUnstated' | 'to' | 'orient' | 'keepSigned' | 'weldTolerance'>;

/** A file's bytes; or a Blob or File, in a worker only (read there with FileReaderSync as the core reads it: a streamed binary STL window by window, any other file whole, once). */
export type FileData = ArrayBuffer | ArrayBufferView | string | Blob;
export interface Companion { name: string; data: FileData }

/** A file's triangles and what `check` finds wrong with its edges, for a 3D view (float32 coordinates as read). */
export interface MeshView {
  exitCode: number;
  error?: string;
  /** The shells (edge-connected parts), largest volume first: role solid, cavity, inside-out, nested (inside another), open or undecided; crosses: it crosses another shell. */
  shells: { role: string; faces: number; volume: number | null; crosses: boolean }[];
  /** How many edges of each kind (an edge may be of several). */
  edges: { boundary: number; nonmanifold: number; misoriented: number; unbalanced: number };
  positions: Float32Array;
  /** The faces' fan triangles, three vertex indices each. */
  triangles: Uint32Array;
  /** Each triangle's shell (index in shells). */
  triangleShell: Uint32Array;
  /** The first edgeLimit edges with a problem: two end points (six floats) each. */
  problemEdges: Float32Array;
  /** Each listed edge's problems: bits 1 boundary, 2 non-manifold, 4 misoriented, 8 unbalanced. */
  problems: Uint8Array;
}

export interface Polyvol {
  volume(data: FileData, name: string, options?: Options, companions?: Companion[]): Answer;
  measure(data: FileData, name: string, options?: Options, companions?: Companion[]): Answer;
  check(data: FileData, name: string, options?: Options, companions?: Companion[]): Answer;
  overlap(dataA: FileData, nameA: string, dataB: FileData, nameB: string, options?: OverlapOptions): OverlapAnswer;
  /** member: an archive's member; edgeLimit: at most that many problem edges listed (200000). */
  mesh(data: FileData, name: string, options?: { member?: string; edgeLimit?: number; companions?: Companion[] }): MeshView;
  run(command: 'volume' | 'measure' | 'check' | 'overlap', files: { name: string; data: FileData; companion?: boolean }[], options?: Options):
    { exitCode: number; stdout: string; messages: string[]; csv?: string; noteWords?: Record<string, string> };
}

/** A module of its own (each holds its memory). */
export function createPolyvol(): Promise<Polyvol>;
export function volume(data: FileData, name: string, options?: Options, companions?: Companion[]): Promise<Answer>;
export function measure(data: FileData, name: string, options?: Options, companions?: Companion[]): Promise<Answer>;
export function check(data: FileData, name: string, options?: Options, companions?: Companion[]): Promise<Answer>;
export function overlap(dataA: FileData, nameA: string, dataB: FileData, nameB: string, options?: OverlapOptions): Promise<OverlapAnswer>;
export function mesh(data: FileData, name: string, options?: { member?: string; edgeLimit?: number; companions?: Companion[] }): Promise<MeshView>;
