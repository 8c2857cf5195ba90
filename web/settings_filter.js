// What the settings form shows (docs/settings.md, "The settings page"): the
// rows whose condition holds for this platform and for the values in the
// form as they stand (a drive changed to hbridge shows its PWM rows before
// it is saved), and of those the ones a search's words all find.
'use strict';

const rotordSettingsFilter = (() => {
  /**
   * Whether a row's condition (the settings table's "when") holds. The
   * grammar is the core's (settings/applies.cpp): alternatives joined by
   * ';', terms joined by '&'; a term is a key that is on (not 0, not
   * empty) or key=choice|choice. "platform" is the firmware's; a schema that names
   * none shows every platform's rows.
   */
  function holds(when, platform, valueOf) {
    if (!when) return true;
    return when.split(';').some((alternative) => alternative.split('&').every((term) => {
      const [key, choices] = term.split('=');
      if (key === 'platform') return !platform || choices.split('|').includes(platform);
      const v = valueOf(key);
      if (choices === undefined) return v === true || (typeof v === 'number' && v !== 0) || (typeof v === 'string' && v !== '');
      return choices.split('|').includes(String(v));
    }));
  }

  /** The words a row is found by: its label, key, help, group and choices. */
  function words(d) {
    const help = typeof rotordSettingsHelp === 'object' ? rotordSettingsHelp[d.key] : '';
    return [d.label, d.key, help, d.group, d.unit, ...(d.choices || [])].join(' ').toLowerCase();
  }

  /** Whether every word of the query is in the row's words. */
  function found(d, query) {
    const wanted = query.toLowerCase().split(/\s+/).filter(Boolean);
    if (!wanted.length) return true;
    const text = words(d);
    return wanted.every((w) => text.includes(w));
  }

  return { holds, found };
})();
