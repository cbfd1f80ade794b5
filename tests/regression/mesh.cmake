# fin-mesh on a coarse default fin: the planform mesh (CGAL), structural mesh and closed IBM
# surface. Catches any change of the meshing that would move nodes, renumber elements or change
# ray sections; the numbers are geometric, so the tolerances are tight.
if(TARGET fin-mesh)
  finverse_add_regression(STAGE mesh CASE coarse_fin
                          COMMAND $<TARGET_FILE:fin-mesh> --mesh @OUT@/mesh.h5 --vtu @OUT@/mesh.vtu
                                  --max-edge 0.08 --threads 1)
endif()
