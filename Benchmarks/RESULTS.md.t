 vtkQuadricDecimation                                                   0.904 
 vtkDecimatePro                                                         0.612 
 vtkQuadricClustering                                                   0.0182 
 vtkBinnedDecimation                                                    0.0039 
 vtkQuadricDecimation chained (whole hierarchy)                         0.907 
 vtkTriangleCollapseDecimation (whole hierarchy)                        0.424 
 vtkTriangleCollapseDecimation strict greedy (whole hierarchy)          0.423 
 vtkTriangleCollapseDecimation paper placement (whole hierarchy)        0.561 
 vtkTriangleCollapseDecimation uniform weights (whole hierarchy)        0.372 
 vtkTriangleCollapseDecimation paper cost (whole hierarchy)             0.422 
 vtkTriangleCollapseDecimation flipped edges (whole hierarchy)          0.435 
 vtkTriangleCollapseDecimation independent sets (whole hierarchy)       0.769 
 vtkTriangleCollapseDecimation triangles only (whole hierarchy)         0.402 
 vtkTriangleCollapseDecimation curvature (whole hierarchy)              1.642 
 vtkTriangleCollapseDecimation curvature strict greedy (whole hierarchy)   2.103 
 vtkTriangleCollapseDecimation curvature paper weight (whole hierarchy)   2.921 
 vtkVertexClusterOctree (whole hierarchy)                               0.309 
 vtkVertexClusterOctree flipped edges (whole hierarchy)                 0.429 
 vtkVertexClusterOctree free topology (whole hierarchy)                 0.243 
 vtkQuadricDecimation                                                   4.674 
 vtkDecimatePro                                                         3.862 
 vtkQuadricClustering                                                   0.0835 
 vtkBinnedDecimation                                                    0.0171 
 vtkQuadricDecimation chained (whole hierarchy)                         5.301 
 vtkTriangleCollapseDecimation (whole hierarchy)                        2.002 
 vtkTriangleCollapseDecimation strict greedy (whole hierarchy)          2.587 
 vtkTriangleCollapseDecimation paper placement (whole hierarchy)        2.923 
 vtkTriangleCollapseDecimation uniform weights (whole hierarchy)        2.184 
 vtkTriangleCollapseDecimation paper cost (whole hierarchy)             2.312 
 vtkTriangleCollapseDecimation flipped edges (whole hierarchy)          2.749 
