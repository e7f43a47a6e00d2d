// The progress of one worker job as the action bar shows it: the worker
// reports (fraction, stage) pairs whose fraction may step back (a stage
// reports its own 0..1, a nested stage restarts); the bar only moves
// forward, with the stage's name, the elapsed time and an estimate of the
// time left. Pure logic (no DOM): the action bar draws it.

/** A duration in seconds as the bar says it: '8 s', '1 min 05 s'. */
export function duration(seconds) {
  const s = Math.max(0, Math.round(seconds));
  if (s < 60) return `${s} s`;
  const m = Math.floor(s / 60);
  return `${m} min ${String(s % 60).padStart(2, '0')} s`;
}

export class JobProgress {
  /** @param {string} stage the job's first stage; now: the clock in ms */
  constructor(stage = '', now = 0) {
    this.start = now;
    this.fraction = 0;
    this.stage = stage;
    this.stages = stage ? [stage] : [];
  }

  /**
   * Takes a report; returns true when the stage changed. A fraction below
   * the shown one keeps the shown one; within a stage that restarts from 0
   * the bar moves on over what is left, so it never goes backwards.
   */
  report(fraction, stage, now) {
    let f = Math.min(1, Math.max(0, Number(fraction) || 0));
    const changed = Boolean(stage) && stage !== this.stage;
    if (changed) {
      this.stage = stage;
      if (!this.stages.includes(stage)) this.stages.push(stage);
      this.base = f < this.fraction ? this.fraction : null;
    }
    // A stage that reports its own 0..1: mapped onto the rest of the bar.
    if (this.base !== null && this.base !== undefined) f = this.base + (1 - this.base) * f * 0.5;
    this.fraction = Math.max(this.fraction, f);
    this.now = now;
    return changed;
  }

  /** Seconds since the job started. */
  elapsed(now = this.now ?? this.start) {
    return (now - this.start) / 1000;
  }

  /** Seconds left by the rate so far, or null when too early to say (under
   * 5% or 1 s). */
  remaining(now = this.now ?? this.start) {
    const t = this.elapsed(now);
    if (this.fraction < 0.05 || t < 1 || this.fraction >= 1) return null;
    return (t * (1 - this.fraction)) / this.fraction;
  }

  /** '12 s elapsed · about 30 s left'; under a second left by the rate,
   * 'finishing' (the last stages' rate says little). */
  timeText(now = this.now ?? this.start) {
    const left = this.remaining(now);
    const rest = left === null ? [] : [left < 1.5 ? 'finishing' : `about ${duration(left)} left`];
    return [`${duration(this.elapsed(now))} elapsed`, ...rest].join(' · ');
  }

  /** 'mesh: tetrahedra · 12 s elapsed · about 30 s left'. */
  text(now = this.now ?? this.start) {
    return `${this.stage} · ${this.timeText(now)}`;
  }
}
