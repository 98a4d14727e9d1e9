// Typed calls to the homesim JSON API (src/homesim/serve). Every error answer has the
// shape {"error": {"kind", "message", "line"?}}; `ApiError` carries it.

export interface Home { name: string; geometry: boolean }
/** A row of the server's action catalog (`ActionSpec.to_dict()`); the editor's only
 * source of per-action facts. */
export interface Action {
  key: string; name: string; arity: number; category: string; animated: boolean;
  description: string;
  connector: string | null; // the word between the two objects of a block (PutBack: "on")
  aliases: string[]; // other spellings of the key, as data sets write it
  needs: string[][][]; // per argument, requirements: properties of which one is needed
}
export interface Category { id: string; label: string; actions: Action[] }
export interface HomeObject {
  id: number; class_name: string; category: string | null;
  room_id: number | null; room: string | null; properties: string[]; states: string[];
}
export interface Objects { home: string; objects: HomeObject[] }
export interface Problem { index: number; line: number; step: string; message: string }
export interface Validation { ok: boolean; problems: Problem[]; program: string }
/** What kind of precondition a step failed (`homesim.sim.FailureKind`), null when it ran. */
export type FailureKind =
  | "missing" | "unreachable" | "not_facing" | "enclosed" | "not_held" | "hands_full"
  | "posture" | "already" | "affordance" | "state";
/** A step's `line` is null when repair inserted it (it has no block). */
export interface StepResult {
  index: number; line: number | null; step: string; ok: boolean; reason: string | null;
  kind: FailureKind | null; summary: string;
}
export interface Insertion { index: number; step: string; reason: string; before: number }
export interface Execution {
  executable: boolean; failed_step: number | null; failed_line: number | null;
  reason: string | null; kind: FailureKind | null; message: string; steps: StepResult[];
  not_run: { index: number; line: number | null; step: string }[];
  repair: {
    program: string; insertions: Insertion[]; executable_before: boolean;
    message_before: string;
  } | null;
}
/** A program written for a description (`homesim learn write`) and its run in the home. */
export interface Written {
  program: string; steps: string[]; title: string; title_given: boolean;
  executable: boolean; run: Execution;
}
export interface Frame { index: number; line: number; url: string }
export interface RenderJob {
  id: string; url: string; kind: "keyframes" | "video";
  status: "queued" | "running" | "done" | "failed" | "cancelled";
  total: number; // key frames; of a video, its frames (0 until the program is animated)
  ready: number; // key frames ready; of a video, frames drawn so far
  frames: Frame[];
  video: string | null; // the MP4's URL once a video job is done
  fps?: number;
  error: { status: number; kind: string; message: string; line?: number; limit?: string } | null;
}

export class ApiError extends Error {
  constructor(readonly status: number, message: string, readonly line: number | null) {
    super(message);
  }
}

async function call<T>(path: string, body?: unknown): Promise<T> {
  const init: RequestInit = body === undefined ? {} : {
    method: "POST",
    headers: { "content-type": "application/json" },
    body: JSON.stringify(body),
  };
  const response = await fetch(`api/${path}`, init);
  const data = await response.json().catch(() => null);
  if (!response.ok) {
    const error = data?.error ?? {};
    throw new ApiError(response.status, error.message ?? `HTTP ${response.status}`,
      typeof error.line === "number" ? error.line : null);
  }
  return data as T;
}

export const api = {
  homes: () => call<{ default: string; homes: Home[] }>("homes"),
  actions: () => call<{ categories: Category[] }>("actions"),
  objects: (home: string) => call<Objects>(`homes/${encodeURIComponent(home)}/objects`),
  validate: (program: string, home: string) => call<Validation>("validate", { program, home }),
  execute: (program: string, home: string) => call<Execution>("execute", { program, home }),
  write: (description: string, title: string | null, home: string) =>
    call<Written>("write", { description, title, home }),
  render: (program: string, home: string) => call<RenderJob>("render", { program, home }),
  renderVideo: (program: string, home: string, fps: number) =>
    call<RenderJob>("render/video", { program, home, fps }),
  renderStatus: (id: string) => call<RenderJob>(`render/${encodeURIComponent(id)}`),
};

/** The URL of one key frame (a PNG), relative to the page like every API call. */
export const frameUrl = (id: string, index: number): string =>
  `api/render/${encodeURIComponent(id)}/frames/${index}`;

/** The URL of a video job's MP4, relative to the page like every API call. */
export const videoUrl = (id: string): string => `api/render/${encodeURIComponent(id)}/video`;

/** Poll a render job, calling `onUpdate` with each status, until it is done (resolves with
 * it) or failed or cancelled (throws its error). */
async function follow(job: RenderJob, onUpdate: (job: RenderJob) => void,
  pollMs: number): Promise<RenderJob> {
  for (;;) {
    onUpdate(job);
    if (job.status === "failed" || job.status === "cancelled") {
      const error = job.error;
      throw new ApiError(error?.status ?? 500, error?.message ?? `render ${job.status}`,
        typeof error?.line === "number" ? error.line : null);
    }
    if (job.status === "done") return job;
    await new Promise((resolve) => window.setTimeout(resolve, pollMs));
    job = await api.renderStatus(job.id);
  }
}

/** Queue a render and call `onFrame` for each key frame as it is drawn; resolves with the
 * finished job, or throws the job's error. */
export async function renderKeyFrames(program: string, home: string,
  onFrame: (frame: Frame, job: RenderJob) => void, pollMs = 300): Promise<RenderJob> {
  let shown = 0;
  return follow(await api.render(program, home), (job) => {
    for (const frame of job.frames.slice(shown)) onFrame(frame, job);
    shown = Math.max(shown, job.frames.length);
  }, pollMs);
}

/** Queue a video of the whole program and call `onProgress` with each status (frames drawn
 * of the total); resolves with the finished job (its MP4 at `videoUrl(job.id)`), or throws
 * the job's error. */
export async function renderVideo(program: string, home: string, fps: number,
  onProgress: (job: RenderJob) => void, pollMs = 400): Promise<RenderJob> {
  return follow(await api.renderVideo(program, home, fps), onProgress, pollMs);
}
