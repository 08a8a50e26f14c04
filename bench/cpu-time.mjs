// CPU time of the browser this process launched, by part, from Linux's
// /proc (elsewhere: null). On a machine whose cores other work shares, a
// drop's wall clock moves with that work, while the CPU milliseconds each
// part of Chromium spends on it move far less: they tell which part a change
// made cheaper. The parts: `worker` (the renderer's DedicatedWorker threads:
// the pipeline worker and its pthreads), `pool` (the renderer's thread pool:
// V8's background compiles, optimised WebAssembly code among them, and its
// concurrent GC), `main` (the page's main thread), `gpu` (the GPU process:
// SwiftShader rasterises there), `other` (the browser process, the
// renderer's compositor, the network service, …).
import { readFileSync, readdirSync } from 'node:fs';

// Clock ticks per second of utime/stime (sysconf(_SC_CLK_TCK); 100 on Linux).
const MS_PER_TICK = 10;

/** The parent, the CPU time (utime + stime, in ticks) and the command name of /proc/<pid>[/task/<tid>]/stat. */
function stat(path) {
  const text = readFileSync(path, 'utf8');
  const fields = text.slice(text.lastIndexOf(')') + 2).split(' ');
  return { ppid: Number(fields[1]), ticks: Number(fields[11]) + Number(fields[12]), comm: text.slice(text.indexOf('(') + 1, text.lastIndexOf(')')) };
}

const numbered = (dir) => readdirSync(dir).filter((d) => /^\d+$/.test(d));

/** The part a thread of a process of type `type` (Chromium's --type, '' for the browser) belongs to. */
function part(type, pid, tid, comm) {
  if (type === 'gpu-process') return 'gpu';
  if (type !== 'renderer') return 'other';
  if (tid === pid) return 'main';
  if (comm.startsWith('DedicatedWorker')) return 'worker';
  if (comm.startsWith('ThreadPoolForeg')) return 'pool';
  return 'other';
}

/** Milliseconds of CPU so far of every thread of this process's descendants, summed by part; null without /proc. */
export function browserCpu() {
  let pids;
  try {
    pids = numbered('/proc');
  } catch {
    return null;
  }
  const parent = new Map();
  for (const pid of pids) {
    try {
      parent.set(pid, String(stat(`/proc/${pid}/stat`).ppid));
    } catch {
      // ended meanwhile
    }
  }
  const mine = (pid) => {
    for (let p = parent.get(pid), hops = 0; p && hops < 32; p = parent.get(p), hops++) if (p === String(process.pid)) return true;
    return false;
  };
  const sums = { worker: 0, pool: 0, main: 0, gpu: 0, other: 0 };
  for (const pid of parent.keys()) {
    if (!mine(pid)) continue;
    try {
      const type = /--type=([a-z-]+)/.exec(readFileSync(`/proc/${pid}/cmdline`, 'utf8'))?.[1] ?? '';
      for (const tid of numbered(`/proc/${pid}/task`)) {
        const { ticks, comm } = stat(`/proc/${pid}/task/${tid}/stat`);
        sums[part(type, pid, tid, comm)] += ticks * MS_PER_TICK;
      }
    } catch {
      // a process or thread that ended meanwhile
    }
  }
  return sums;
}

/** `after` − `before` by part, with their sum as `all`; null if either is. */
export function cpuSpent(before, after) {
  if (!before || !after) return null;
  const spent = Object.fromEntries(Object.keys(after).map((k) => [k, after[k] - (before[k] ?? 0)]));
  spent.all = Object.values(spent).reduce((s, ms) => s + ms, 0);
  return spent;
}
