#!/usr/bin/env python3
"""Flat-shaded close-up of a face and its poses side by side: only the triangles whose neutral
centroid lies in BOX (the mesh's own units), turned triangles red, for folds too small to see in
scripts/side_view.py's whole-face views. Needs python3-pil and numpy.

    BOX=xmin,xmax,ymin,ymax [YAW=deg] [SIZE=px] python3 scripts/zoom_view.py NEUTRAL.obj POSED.obj [MORE.obj ...] OUT.png

YAW=180 looks from behind the skin (a fold that turned a triangle to face into the head is hidden
from the front)."""
import math
import os
import sys

import numpy as np
from PIL import Image, ImageDraw

from obj_io import load
from PIL import Image, ImageDraw
import numpy as np
base,tris=load(sys.argv[1]); meshes=[np.array(base)]+[np.array(load(p)[0]) for p in sys.argv[2:-1]]
T=np.array(tris); B=meshes[0]
x0,x1,y0,y1=[float(v) for v in os.environ['BOX'].split(',')]
yaw=math.radians(float(os.environ.get('YAW','0'))); size=int(os.environ.get('SIZE','600'))
cent=B[T].mean(1); sel=(cent[:,0]>=x0)&(cent[:,0]<=x1)&(cent[:,1]>=y0)&(cent[:,1]<=y1)
cz=cent[sel][:,2].mean(); cx,cy=(x0+x1)/2,(y0+y1)/2
R=np.array([[math.cos(yaw),0,math.sin(yaw)],[0,1,0],[-math.sin(yaw),0,math.cos(yaw)]])
scale=0.95*size/max(x1-x0,y1-y0)
light=np.array([0.3,0.4,0.87]); nb=np.cross(B[T[:,1]]-B[T[:,0]],B[T[:,2]]-B[T[:,0]])
panels=[]
for V in meshes:
    img=Image.new('RGB',(size,size),'white'); d=ImageDraw.Draw(img)
    W=(V-np.array([cx,cy,cz]))@R.T
    n=np.cross(V[T[:,1]]-V[T[:,0]],V[T[:,2]]-V[T[:,0]]); flip=(n*nb).sum(1)<0
    polys=[]
    for t in np.where(sel)[0]:
        p=W[T[t]]; nn=n[t]; l=np.linalg.norm(nn) or 1; sh=abs(nn@light)/l
        col=(255,int(60*sh),int(60*sh)) if flip[t] else (int(60+180*sh),int(60+170*sh),int(60+160*sh))
        polys.append((p[:,2].mean(),[(size/2+q[0]*scale, size/2-q[1]*scale) for q in p],col))
    polys.sort(key=lambda q:q[0])
    for _,pts,col in polys: d.polygon(pts,fill=col)
    panels.append(img)
out=Image.new('RGB',(size*len(panels)+10*(len(panels)-1),size),'black')
for k,p in enumerate(panels): out.paste(p,(k*(size+10),0))
out.save(sys.argv[-1]); print('wrote',sys.argv[-1])
