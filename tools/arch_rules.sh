#!/usr/bin/env bash
# tools/arch_rules.sh: the data and figures of docs/arch-spectra.md "An arch design rule" (seconds, no simulation).
set -euo pipefail
R=${ROCKING:-target/release/rocking}
mkdir -p docs/data/arch-rules
$R arch suite docs/data/arch/oas-RSN*.json --name "far field (44)" --svg docs/figures/arch-suite-farfield > docs/data/arch-rules/suite-farfield-N8.txt
$R arch suite docs/data/arch-nearfield/oas-RSN*.json --name "near field (56)" --svg docs/figures/arch-suite-nearfield > docs/data/arch-rules/suite-nearfield-N8.txt
$R arch suite docs/data/arch20/oas-RSN*.json --name "far field (44)" --svg docs/figures/arch-suite-farfield-N20 > docs/data/arch-rules/suite-farfield-N20.txt
$R arch suite docs/data/arch-t020/oas-RSN*.json --name "far field (44), t/R 0.20" --svg docs/figures/arch-suite-farfield-t020 > docs/data/arch-rules/suite-farfield-N8-t020.txt
$R arch suite docs/data/arch-t020-nearfield/oas-RSN*.json --name "near field (56), t/R 0.20" --svg docs/figures/arch-suite-nearfield-t020 > docs/data/arch-rules/suite-nearfield-N8-t020.txt
$R arch suite docs/data/arch20-nearfield/oas-RSN*.json --name "near field (56)" --svg docs/figures/arch-suite-nearfield-N20 > docs/data/arch-rules/suite-nearfield-N20.txt
$R arch suite docs/data/arch-t012/oas-RSN*.json --name "far field (44), t/R 0.12" --svg docs/figures/arch-suite-farfield-t012 > docs/data/arch-rules/suite-farfield-N8-t012.txt
$R arch suite docs/data/arch-t012-nearfield/oas-RSN*.json --name "near field (56), t/R 0.12" --svg docs/figures/arch-suite-nearfield-t012 > docs/data/arch-rules/suite-nearfield-N8-t012.txt
$R arch suite docs/data/arch-t011/oas-RSN*.json --name "far field (44), t/R 0.11" --svg docs/figures/arch-suite-farfield-t011 > docs/data/arch-rules/suite-farfield-N8-t011.txt
$R arch suite docs/data/arch-t011-nearfield/oas-RSN*.json --name "near field (56), t/R 0.11" --svg docs/figures/arch-suite-nearfield-t011 > docs/data/arch-rules/suite-nearfield-N8-t011.txt
$R arch suite docs/data/arch-t0105/oas-RSN*.json --name "far field (44), t/R 0.105" --svg docs/figures/arch-suite-farfield-t0105 > docs/data/arch-rules/suite-farfield-N8-t0105.txt
$R arch suite docs/data/arch-t0105-nearfield/oas-RSN*.json --name "near field (56), t/R 0.105" --svg docs/figures/arch-suite-nearfield-t0105 > docs/data/arch-rules/suite-nearfield-N8-t0105.txt
$R arch suite docs/data/arch6/oas-RSN*.json --name "far field (44), 6 voussoirs" --svg docs/figures/arch-suite-farfield-N6 > docs/data/arch-rules/suite-farfield-N6.txt
$R arch suite docs/data/arch6-nearfield/oas-RSN*.json --name "near field (56), 6 voussoirs" --svg docs/figures/arch-suite-nearfield-N6 > docs/data/arch-rules/suite-nearfield-N6.txt
$R arch suite docs/data/arch-e150/oas-RSN*.json --name "far field (44), embrace 150°" --svg docs/figures/arch-suite-farfield-e150 > docs/data/arch-rules/suite-farfield-N8-e150.txt
$R arch suite docs/data/arch-e150-nearfield/oas-RSN*.json --name "near field (56), embrace 150°" --svg docs/figures/arch-suite-nearfield-e150 > docs/data/arch-rules/suite-nearfield-N8-e150.txt
$R arch suite docs/data/arch4/oas-RSN*.json --name "far field (44), 4 voussoirs" --svg docs/figures/arch-suite-farfield-N4 > docs/data/arch-rules/suite-farfield-N4.txt
$R arch suite docs/data/arch4-nearfield/oas-RSN*.json --name "near field (56), 4 voussoirs" --svg docs/figures/arch-suite-nearfield-N4 > docs/data/arch-rules/suite-nearfield-N4.txt
$R arch suite docs/data/arch-e120/oas-RSN*.json --name "far field (44), embrace 120°" --svg docs/figures/arch-suite-farfield-e120 > docs/data/arch-rules/suite-farfield-N8-e120.txt
$R arch suite docs/data/arch-e120-nearfield/oas-RSN*.json --name "near field (56), embrace 120°" --svg docs/figures/arch-suite-nearfield-e120 > docs/data/arch-rules/suite-nearfield-N8-e120.txt
$R arch suite docs/data/arch5/oas-RSN*.json --name "far field (44), 5 voussoirs" --svg docs/figures/arch-suite-farfield-N5 > docs/data/arch-rules/suite-farfield-N5.txt
$R arch suite docs/data/arch5-nearfield/oas-RSN*.json --name "near field (56), 5 voussoirs" --svg docs/figures/arch-suite-nearfield-N5 > docs/data/arch-rules/suite-nearfield-N5.txt
$R arch suite docs/data/arch12/oas-RSN*.json --name "far field (44), 12 voussoirs" --svg docs/figures/arch-suite-farfield-N12 > docs/data/arch-rules/suite-farfield-N12.txt
$R arch suite docs/data/arch12-nearfield/oas-RSN*.json --name "near field (56), 12 voussoirs" --svg docs/figures/arch-suite-nearfield-N12 > docs/data/arch-rules/suite-nearfield-N12.txt
# The fit set: far field, 8 voussoirs, t/R 0.15. The test sets, out of sample: other records
# (near field) or other arches (20, 12, 6, 5 and 4 voussoirs; t/R 0.20, 0.12, 0.11 and 0.105; embrace
# 150° and 120°), where a fixed t1 is not scored.
args=(--fit docs/data/arch/oas-RSN*.json
  --test docs/data/arch-nearfield/oas-RSN*.json docs/data/arch20/oas-RSN*.json
         docs/data/arch20-nearfield/oas-RSN*.json docs/data/arch-t020/oas-RSN*.json
         docs/data/arch-t020-nearfield/oas-RSN*.json docs/data/arch-t012/oas-RSN*.json
         docs/data/arch-t012-nearfield/oas-RSN*.json docs/data/arch-t011/oas-RSN*.json
         docs/data/arch-t011-nearfield/oas-RSN*.json docs/data/arch6/oas-RSN*.json
         docs/data/arch6-nearfield/oas-RSN*.json docs/data/arch-e150/oas-RSN*.json
         docs/data/arch-e150-nearfield/oas-RSN*.json docs/data/arch-t0105/oas-RSN*.json
         docs/data/arch-t0105-nearfield/oas-RSN*.json docs/data/arch4/oas-RSN*.json
         docs/data/arch4-nearfield/oas-RSN*.json docs/data/arch-e120/oas-RSN*.json
         docs/data/arch-e120-nearfield/oas-RSN*.json docs/data/arch5/oas-RSN*.json
         docs/data/arch5-nearfield/oas-RSN*.json docs/data/arch12/oas-RSN*.json
         docs/data/arch12-nearfield/oas-RSN*.json
  --tp docs/data/t1-farfield.json --tp docs/data/t1-nearfield.json
  --names "far field 8,near field 8,far field 20,near field 20,far field 8 t/R 0.20,near field 8 t/R 0.20,far field 8 t/R 0.12,near field 8 t/R 0.12,far field 8 t/R 0.11,near field 8 t/R 0.11,far field 6,near field 6,far field 8 embrace 150,near field 8 embrace 150,far field 8 t/R 0.105,near field 8 t/R 0.105,far field 4,near field 4,far field 8 embrace 120,near field 8 embrace 120,far field 5,near field 5,far field 12,near field 12")
$R arch rules "${args[@]}" --svg docs/figures/arch-rules.svg > docs/data/arch-rules/rules.txt
$R arch rules "${args[@]}" --json > docs/data/arch-rules/rules.json
# The figure draws nine set colours, then repeats them: three more figures draw the fit set with the
# sets computed after t/R 0.12: the thinner arches (t/R 0.11 and 0.105), the other numbers of voussoirs
# (12, 6, 5, 4) and the segmental arches (embrace 150° and 120°), nine sets at most each.
tp=(--tp docs/data/t1-farfield.json --tp docs/data/t1-nearfield.json)
thin=(--fit docs/data/arch/oas-RSN*.json
  --test docs/data/arch-t011/oas-RSN*.json docs/data/arch-t011-nearfield/oas-RSN*.json
         docs/data/arch-t0105/oas-RSN*.json docs/data/arch-t0105-nearfield/oas-RSN*.json
  --names "far field 8,far field 8 t/R 0.11,near field 8 t/R 0.11,far field 8 t/R 0.105,near field 8 t/R 0.105")
$R arch rules "${thin[@]}" "${tp[@]}" --svg docs/figures/arch-rules-thin.svg > /dev/null
voussoirs=(--fit docs/data/arch/oas-RSN*.json
  --test docs/data/arch12/oas-RSN*.json docs/data/arch12-nearfield/oas-RSN*.json
         docs/data/arch6/oas-RSN*.json docs/data/arch6-nearfield/oas-RSN*.json
         docs/data/arch5/oas-RSN*.json docs/data/arch5-nearfield/oas-RSN*.json
         docs/data/arch4/oas-RSN*.json docs/data/arch4-nearfield/oas-RSN*.json
  --names "far field 8,far field 12,near field 12,far field 6,near field 6,far field 5,near field 5,far field 4,near field 4")
$R arch rules "${voussoirs[@]}" "${tp[@]}" --svg docs/figures/arch-rules-voussoirs.svg > /dev/null
embrace=(--fit docs/data/arch/oas-RSN*.json
  --test docs/data/arch-e150/oas-RSN*.json docs/data/arch-e150-nearfield/oas-RSN*.json
         docs/data/arch-e120/oas-RSN*.json docs/data/arch-e120-nearfield/oas-RSN*.json
  --names "far field 8,far field 8 embrace 150,near field 8 embrace 150,far field 8 embrace 120,near field 8 embrace 120")
$R arch rules "${embrace[@]}" "${tp[@]}" --svg docs/figures/arch-rules-embrace.svg > /dev/null
