# Sourced by cli tests: two J2 tin spheres (finite strain) in
# prm/default.prm, 6 steps on a 0.5 mm mesh with graphics every 2 steps.
# Sets prm (the scene), j2 (the material and steps), pair (the spheres
# touching each other and a 5 mm die, refined where they touch) and free
# (the spheres apart, pressed by the punches only).
prm="$SOURCE_DIR/prm/default.prm"
j2=(--set "Material/Model=J2 plasticity" --set "Material/Finite strain=true"
    --set "Mesh/Element size=0.5" --set "Time stepping/Number of steps=6"
    --set "Output/Interval=2")
pair=("${j2[@]}" --set "Particles/Centres=-1.25,0,1.25; 1.25,0,1.25"
      --set "Mesh/Refinement directions=0,0,1; 0,0,-1; 1,0,0; -1,0,0"
      --set "Mesh/Refined element size=0.2" --set "Tools/Die wall/Diameter=5.0"
      --set "Tools/Upper punch/Displacement history=0:0, 1:0.15")
free=("${j2[@]}" --set "Particles/Centres=-1.25,0,1.25; 1.25,0,1.25"
      --set "Tools/Upper punch/Displacement history=0:0, 1:0.12")
