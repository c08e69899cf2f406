#!/bin/bash
# Every numeric option of every rcbench subcommand states its unit in its
# help text (the issue: "--help documents every option with its unit and
# default"), and CLI11 prints its default. A new option without a unit fails
# here, naming the option.
set -u
rcbench="$1"
status=0
# A unit in parentheses: SI or derived units, counts, ratios, or the
# domain-specific units the suite uses (nodes per ray, core cycles).
unit='\((count|count N|unitless|unitless fraction|fraction|probability|index|index k|record index|cells|m|s|rad|rad/m|J|m/s|rad/s|1/m|1/sensor update|rad\^2/rad\^2|rad\^2/m\^2|m\^2/m\^2|m\^2/rad\^2|updates|nodes per ray|nodes per query|tree nodes per kernel query|core cycles|cycles|m, m, rad|deg|Hz|nats)[;,): ]'
subcommands=$("$rcbench" --help | awk '/^Subcommands:/{on=1; next} on && /^  [a-z]/{print $1}')
[ -n "$subcommands" ] || { echo "no subcommands found in 'rcbench --help'"; exit 1; }
for sub in $subcommands; do
  # One line per option: CLI11 wraps long descriptions onto lines indented
  # by 20 or more spaces.
  lines=$("$rcbench" "$sub" --help | awk '/^  -/{if(l)print l; l=$0; next}
      /^                    /{sub(/^ +/," "); l=l $0; next} {if(l)print l; l=""} END{if(l)print l}')
  while IFS= read -r line; do
    case "$line" in *" INT"*|*" UINT"*|*" FLOAT"*) ;; *) continue ;; esac
    if ! printf '%s\n' "$line" | grep -Eq "$unit"; then
      echo "rcbench $sub: option without a unit: $(printf '%s' "$line" | sed -E 's/ +/ /g' | cut -c1-160)"
      status=1
    fi
    # A default is printed unless the option has none by design (optional
    # values such as --threshold or --initial-pose say what happens without).
    if ! printf '%s\n' "$line" | grep -Eq '(INT|UINT|FLOAT)(:[^=]*)?=[^ ]|default|without|x [0-9]|instead|required'; then
      echo "rcbench $sub: option without a default: $(printf '%s' "$line" | sed -E 's/ +/ /g' | cut -c1-160)"
      status=1
    fi
  done <<< "$lines"
done
[ $status -eq 0 ] && echo "every numeric option of:" $subcommands "states its unit and default"
exit $status
