# Settings shared by the reference images and the regression renders: small images, short
# paths, few lights per frame (the estimator is unbiased at any count), two threads.
set(TRS_REFERENCE_SETTINGS --width 64 --height 36 --max-depth 3 --lights 20000 --threads 2)
set(TRS_REFERENCE_SPP 1024)
set(TRS_REFERENCE_SCENES neon-sign gradient-screen mosaic tile-emitter lantern night-street video-wall)
# The real assets of scenes/real (scenes/real/README.md), by their path under scenes/.
set(TRS_REFERENCE_REAL_SCENES real/damaged-helmet real/lantern real/boombox real/toy-car real/energy-ball
    real/spell-disk real/space-exploration real/terrarium-bots real/spaceship-corridor real/love-neon real/glass-house)
# The material scenes of scenes/materials: alpha, normal maps, texture transforms and UV sets, and
# the material extensions (transmission, volume, ior and specular, clearcoat, sheen).
set(TRS_REFERENCE_MATERIAL_SCENES materials/stained-lamp materials/blend-glass materials/normal-wall
    materials/atlas-sign materials/glass-panes materials/glass-volume materials/ior-specular
    materials/coated-panel materials/sheen-cloth materials/floor-lamp)
