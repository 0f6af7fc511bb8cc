# Sourced by cli tests: the light paper scene (seven J2 tin spheres with
# friction 0.2, prm/single_layer_sn_light.prm) shrunk to 0.24 mm of stroke in
# 8 steps on a 0.6 mm mesh, where the particles press on the punches and the
# die wall. Sets scene and common (options for every run).
scene="$SOURCE_DIR/prm/single_layer_sn_light.prm"
common=(--set "Output/Interval=0" --set "Output/Checkpoint interval=0"
  --set "Mesh/Element size=0.6"
  --set "Tools/Upper punch/Displacement history=0:0, 0.8:0.24"
  --set "Time stepping/Number of steps=8")
