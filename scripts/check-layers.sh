#!/usr/bin/env bash
# Fails when an #include in src/ breaks the layer order (docs/ARCHITECTURE.md): each layer may
# include only itself and the layers below it.
#   core
#   contact, domain, scene, analysis   on core
#   thermo                             on contact
#   sim                                on contact, domain, scene (never analysis)
#   io                                 on sim's settings, books and state layout, never the
#                                      engine itself (sim/simulation.hpp): run/ joins the two
#   run                                on io, sim, analysis
#   validation                         on run, thermo
# apps/, python/ (the Python module), tests/ and bench/ may include any layer.
set -euo pipefail
cd "$(dirname "$0")/.."

declare -A below=(
  [core]=""
  [contact]="core"
  [domain]="core"
  [scene]="core"
  [analysis]="core"
  [thermo]="contact core"
  [sim]="contact domain scene core"
  [io]="sim contact domain scene core"
  [device]="contact core"
  [run]="io sim analysis device contact domain scene core"
  [validation]="run thermo io sim analysis device contact domain scene core"
)

status=0
for dir in src/*/; do
  layer=$(basename "$dir")
  if [[ -z ${below[$layer]+set} ]]; then
    echo "src/$layer: a layer the check does not know; add it to scripts/check-layers.sh"
    status=1
    continue
  fi
  allowed=" $layer ${below[$layer]} "
  while IFS=: read -r file line include; do
    target=${include%%/*}
    if [[ $allowed != *" $target "* ]]; then
      echo "$file:$line: $layer includes $include (allowed: ${below[$layer]:-nothing})"
      status=1
    fi
  done < <(grep -rnoE '^#include "[a-z_]+/[^"]+"' "$dir" | sed -E 's/#include "([^"]+)"/\1/')
done
# The seam for a second backend (docs/ARCHITECTURE.md): the contact laws and what they use are
# plain data and YUXI_HD functions that nvcc compiles too. Their headers include only one
# another and a few standard headers; fmt, io/, std::string, std::variant, the host containers
# and the rest of the host-only world stay out.
seam=(src/core/host_device.hpp src/core/always_inline.hpp src/core/units.hpp src/core/vec3.hpp
  src/core/particle_fields.hpp src/core/particle_view.hpp src/contact/contact_geometry.hpp src/contact/frictional_spring.hpp
  src/contact/rolling_resistance.hpp src/contact/hooke.hpp src/contact/linear_spring_dashpot.hpp
  src/contact/hertz_mindlin.hpp src/contact/luding.hpp src/contact/thermodynamic.hpp
  src/contact/thermodynamic_law.hpp src/core/portable_math.hpp src/core/radial_wave.hpp
  src/core/particle_energy.hpp src/core/quaternion.hpp src/core/free_rotation.hpp
  src/device/step_phases.hpp)
standard=" cmath cstdint cstddef cstring algorithm limits string_view numbers type_traits array "
for header in "${seam[@]}"; do
  while IFS= read -r line; do
    if [[ $line =~ ^#include\ \"([^\"]+)\" ]]; then
      [[ " ${seam[*]} " == *" src/${BASH_REMATCH[1]} "* ]] && continue
      echo "$header: includes ${BASH_REMATCH[1]}, which is not a seam header"
      status=1
    elif [[ $line =~ ^#include\ \<([^\>]+)\> ]]; then
      [[ $standard == *" ${BASH_REMATCH[1]} "* ]] && continue
      echo "$header: includes <${BASH_REMATCH[1]}>, which the seam's headers do not use"
      status=1
    fi
  done < <(grep -E '^#include' "$header")
done

# The file formats know the engine's settings, books and state layout, not the engine.
while IFS=: read -r file line _; do
  echo "$file:$line: io includes the engine (sim/simulation.hpp); join the two in run/"
  status=1
done < <(grep -rnE '^#include "sim/simulation\.hpp"' src/io || true)
if ((status == 0)); then echo "layers: every include follows the layer order"; fi
exit $status
